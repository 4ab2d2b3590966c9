#!/usr/bin/env python3
"""Copies a Mitsuba wheel without the variants the GPU bench does not use on the GPU machine
(every one but cuda_ad_rgb and scalar_rgb: the `--dry` check here runs bench/.venv's full
Mitsuba, not this wheel) and without data/srgb.coeff (the RGB-to-spectrum table of the spectral
variants; the rgb ones rendered the bench scenes without it), so that it and Dr.Jit fit in what a
device call carries.

    python3 bench/gpu/slim_wheel.py mitsuba-X.whl OUT_DIR

A variant is one extension module, mitsuba/VARIANT.cpython-*.so; the RECORD file (the wheel's
list of files, PEP 427) is rewritten without the dropped ones.
"""
import os
import re
import sys
import zipfile

KEEP = {"cuda_ad_rgb", "scalar_rgb"}
VARIANT = re.compile(r"^mitsuba/((?:scalar|llvm|cuda)_[a-z_]+)\.cpython-[^/]*\.so$")


def main(src, out_dir):
    dst = os.path.join(out_dir, os.path.basename(src))
    dropped = 0
    with zipfile.ZipFile(src) as zin, zipfile.ZipFile(dst, "w", zipfile.ZIP_DEFLATED) as zout:
        names = [i.filename for i in zin.infolist()]
        drop = {n for n in names if VARIANT.match(n) and VARIANT.match(n).group(1) not in KEEP}
        drop |= {n for n in names if n == "mitsuba/data/srgb.coeff"}
        for info in zin.infolist():
            if info.filename in drop:
                dropped += info.compress_size
                continue
            data = zin.read(info)
            if info.filename.endswith(".dist-info/RECORD"):
                data = "".join(line for line in data.decode().splitlines(True)
                               if line.split(",")[0] not in drop).encode()
            zout.writestr(info, data, compress_type=zipfile.ZIP_DEFLATED)
    print(f"{dst}: {len(drop)} files left out ({dropped / 2**20:.1f} MiB), "
          f"{os.path.getsize(dst) / 2**20:.1f} MiB")


if __name__ == "__main__":
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    main(sys.argv[1], sys.argv[2])
