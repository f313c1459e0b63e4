#!/usr/bin/env python3
"""Compares the rates.json of two seeds folders, or two trees of such folders, key by key.

    scripts/same-rates.py BEFORE AFTER

BEFORE and AFTER are folders written by `activetouch-cli seeds` (each holding rates.json) or
folders of them (each subfolder compared with its namesake). Keys that hold wall time are left
out. Prints one line per folder and every key that differs; exits 1 if any does.
"""
import json
import pathlib
import sys

TIMING = ("wall", "timing")


def differences(a, b, where="/"):
    if isinstance(a, dict) and isinstance(b, dict):
        out = []
        for k in sorted(set(a) | set(b)):
            if any(t in k for t in TIMING):
                continue
            if k not in a or k not in b:
                out.append(f"{where}{k}: only in {'after' if k in b else 'before'}")
            else:
                out += differences(a[k], b[k], f"{where}{k}/")
        return out
    if isinstance(a, list) and isinstance(b, list):
        if len(a) != len(b):
            return [f"{where}: {len(a)} items before, {len(b)} after"]
        out = []
        for i, (x, y) in enumerate(zip(a, b)):
            out += differences(x, y, f"{where}{i}/")
        return out
    return [] if a == b else [f"{where}: {a!r} before, {b!r} after"]


def folders(root):
    root = pathlib.Path(root)
    if (root / "rates.json").is_file():
        return {".": root}
    return {p.name: p for p in sorted(root.iterdir()) if (p / "rates.json").is_file()}


def main():
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    before, after = folders(sys.argv[1]), folders(sys.argv[2])
    if not before:
        sys.exit(f"{sys.argv[1]}: no rates.json in it or its subfolders")
    bad = 0
    for name in sorted(set(before) | set(after)):
        if name not in before or name not in after:
            print(f"{name}: only {'after' if name in after else 'before'}")
            bad += 1
            continue
        a = json.loads((before[name] / "rates.json").read_text())
        b = json.loads((after[name] / "rates.json").read_text())
        diff = differences(a, b)
        print(f"{name}: {'same' if not diff else f'{len(diff)} differences'}")
        for d in diff[:20]:
            print("   ", d)
        bad += bool(diff)
    sys.exit(1 if bad else 0)


if __name__ == "__main__":
    main()
