#pragma once
// Where the workbench's files are: beside the binary once installed (<prefix>/bin/activetouch
// finds <prefix>/share/activetouch/...), or in the source tree the build came from.
#include <QString>

namespace activetouch {

/// <prefix>/share/activetouch when the running binary sits in <prefix>/bin and that folder holds
/// the resources; empty otherwise (a binary in the build tree).
QString installedDataDirectory();
/// Points the engine at the installed resources (the fingertip layouts) unless
/// ACTIVETOUCH_RESOURCES already names some. Call once at start-up.
void useInstalledResources();
/// The shipped experiments: installed, or the source tree's experiments/.
QString experimentsDirectory();
/// The documentation: installed (<prefix>/share/doc/activetouch), or the source tree's docs/.
QString documentationDirectory();
/// The application icon's folder (activetouch.svg).
QString iconDirectory();

}  // namespace activetouch
