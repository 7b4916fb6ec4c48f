#!/usr/bin/env python3
"""Recomputes the checksums of .tframe, .mta and .tab files in place, as the fuzz targets do before decoding.

Usage: python3 fuzz/fix_checksums.py FILE...

The `tframe` and `mta` targets (fuzz/tframe.cpp, fuzz/mta.cpp) repair the fields a mutation cannot keep
consistent by chance before they hand an input to the reader, so a minimised finding usually has stale
checksums: it fails in the fuzz target but `tessera validate` / `tessera mta info` reject it at the
checksum. Run this on such a file before keeping it in fuzz/crashers/ or fuzz/corpus/, so that it
reproduces through the CLI as well; the targets leave a file with correct checksums unchanged.
- .tframe (docs/tframe-format.md): SHA-256 of bytes 72.. into bytes 40..71.
- .mta (docs/mta-format.md): file size (16..23), metadata size (32..39, from the metadata offset at
  24..31), metadata SHA-256 (40..71), header SHA-256 of bytes 0..95 (96..127).
- .tab (docs/tab-format.md): file size (24..31), the SHA-256 of each section the section table places
  inside the file, header SHA-256 of bytes 0..423 (424..455).
Files that are neither (no magic) are left alone. Standard library only.
"""
import hashlib
import os
import struct
import sys


def fix(data):
    if len(data) >= 72 and data[:8] == b"TSFRAME\x00":
        data[40:72] = hashlib.sha256(bytes(data[72:])).digest()
        return "tframe"
    if len(data) >= 128 and data[:8] == b"TESSMTA\x1a":
        size = len(data)
        meta_offset = struct.unpack_from("<Q", data, 24)[0]
        struct.pack_into("<Q", data, 16, size)
        if 128 <= meta_offset <= size:
            struct.pack_into("<Q", data, 32, size - meta_offset)
            data[40:72] = hashlib.sha256(bytes(data[meta_offset:])).digest()
        data[96:128] = hashlib.sha256(bytes(data[:96])).digest()
        return "mta"
    if len(data) >= 456 and data[:8] == b"TESSTAB\x1a":
        size = len(data)
        struct.pack_into("<Q", data, 24, size)
        for k in range(7):
            offset, length = struct.unpack_from("<QQ", data, 32 + 56 * k + 8)
            if offset <= size and length <= size - offset:
                data[32 + 56 * k + 24:32 + 56 * k + 56] = hashlib.sha256(bytes(data[offset:offset + length])).digest()
        data[424:456] = hashlib.sha256(bytes(data[:424])).digest()
        return "tab"
    return None


def main():
    if len(sys.argv) < 2:
        sys.exit(__doc__)
    for path in sys.argv[1:]:
        with open(path, "rb") as f:
            data = bytearray(f.read())
        before = bytes(data)
        kind = fix(data)
        if kind is None:
            print(f"{path}: not a .tframe, .mta or .tab file, left alone")
            continue
        if bytes(data) == before:
            print(f"{path}: {kind}, checksums already correct")
            continue
        with open(path + ".tmp", "wb") as f:
            f.write(data)
        os.replace(path + ".tmp", path)
        print(f"{path}: {kind}, checksums recomputed")


if __name__ == "__main__":
    main()
