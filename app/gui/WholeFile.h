#pragma once
// Files the window saves (experiments, rig files, a plot's data): written whole or not at all.
#include <QByteArray>
#include <QString>

namespace activetouch {

/// Writes `bytes` to `path` through a temporary file beside it, renamed over `path` once every
/// byte is on the disk. Returns an empty string, or the system's reason it failed; `path` is then
/// as it was before.
QString writeFileWhole(const QString& path, const QByteArray& bytes);

/// The same, throwing std::runtime_error naming `path`, the reason and what to do if it fails.
void writeWholeOrThrow(const QString& path, const QByteArray& bytes);

}  // namespace activetouch
