#!/usr/bin/env python3
"""Checks that every frame of a split render exists and is complete, and lists what to requeue.

    collect_frames.py --out 'frames/frame_####.exr' --frame-range 0:1999 --per-task 8

A frame is complete when its file is whole: a PFM whose header parses and whose size is the
header's plus width x height pixels exactly; a PNG that ends with its IEND chunk; a
single-part scanline OpenEXR whose offset table points inside the file and whose last chunk
ends inside it. memograph writes each frame through a temporary renamed into place, so a
torn write never has the final name; the check catches files cut short afterwards (a copy
that stopped, a full disk). With --per-task (memograph_array.sbatch's PER_TASK) it names the
array tasks that hold the missing frames and prints the sbatch --array list to resubmit.

Exit status: 0 all complete, 1 some missing or incomplete, 2 usage. Python 3, standard
library only.
"""

import argparse
import os
import re
import struct
import sys


def pfm_complete(data):
    match = re.match(rb"(P[Ff])\s+(\d+)\s+(\d+)\s+(\S+)\s", data[:256])
    if not match:
        return False
    channels = 3 if match.group(1) == b"PF" else 1
    width, height = int(match.group(2)), int(match.group(3))
    try:
        if float(match.group(4)) == 0.0:
            return False
    except ValueError:
        return False
    return len(data) == match.end() + width * height * channels * 4


def png_complete(data):
    return (data[:8] == b"\x89PNG\r\n\x1a\n" and len(data) >= 20
            and data[-12:-8] == b"\0\0\0\0" and data[-8:-4] == b"IEND")


# Scanlines per chunk by OpenEXR compression (none, rle, zips, zip, piz, pxr24, b44, b44a,
# dwaa, dwab).
EXR_LINES_PER_CHUNK = [1, 1, 1, 16, 32, 16, 32, 32, 32, 256]


def exr_complete(data):
    if data[:4] != b"\x76\x2f\x31\x01" or len(data) < 8:
        return False
    version = struct.unpack_from("<I", data, 4)[0]
    if version & 0x1200:  # tiled or multi-part: only the magic number is checked
        return True
    at, window, compression = 8, None, None
    while True:  # the header: name, type, size, value; an empty name ends it
        end = data.find(b"\0", at)
        if end < 0:
            return False
        name = data[at:end]
        if not name:
            at = end + 1
            break
        type_end = data.find(b"\0", end + 1)
        if type_end < 0 or type_end + 5 > len(data):
            return False
        size = struct.unpack_from("<i", data, type_end + 1)[0]
        value_at = type_end + 5
        if size < 0 or value_at + size > len(data):
            return False
        if name == b"dataWindow" and size == 16:
            window = struct.unpack_from("<iiii", data, value_at)
        elif name == b"compression" and size == 1:
            compression = data[value_at]
        at = value_at + size
    if window is None or compression is None or compression >= len(EXR_LINES_PER_CHUNK):
        return False
    lines = window[3] - window[1] + 1
    chunks = -(-lines // EXR_LINES_PER_CHUNK[compression])
    if lines <= 0 or at + 8 * chunks > len(data):
        return False
    offsets = struct.unpack_from("<%dQ" % chunks, data, at)
    for offset in offsets:
        if offset + 8 > len(data):
            return False
        chunk_size = struct.unpack_from("<i", data, offset + 4)[0]
        if chunk_size < 0 or offset + 8 + chunk_size > len(data):
            return False
    return True


def frame_complete(path):
    try:
        with open(path, "rb") as f:
            data = f.read()
    except OSError:
        return False
    extension = os.path.splitext(path)[1].lower()
    check = {".pfm": pfm_complete, ".png": png_complete, ".exr": exr_complete}.get(extension)
    return bool(check and check(data))


def frame_path(pattern, frame):
    folder, name = os.path.split(pattern)
    runs = list(re.finditer(r"#+", name))
    if not runs:
        return pattern
    run = runs[0]
    index = str(frame).rjust(len(run.group(0)), "0")
    return os.path.join(folder, name[:run.start()] + index + name[run.end():])


def main(argv):
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--out", required=True, help="the frames' pattern, as given to render --out")
    parser.add_argument("--frame-range", required=True, help="FIRST:LAST, as given to the array")
    parser.add_argument("--per-task", type=int, help="frames per array task (PER_TASK)")
    args = parser.parse_args(argv)
    match = re.fullmatch(r"(\d+):(\d+)", args.frame_range)
    if not match or int(match.group(1)) > int(match.group(2)):
        parser.error("--frame-range takes FIRST:LAST with FIRST <= LAST, not %r" % args.frame_range)
    first, last = int(match.group(1)), int(match.group(2))
    if args.per_task is not None and args.per_task < 1:
        parser.error("--per-task takes a whole number > 0")
    runs = len(re.findall(r"#+", os.path.basename(args.out)))
    if runs > 1 or (runs == 0 and first != last):
        parser.error("--out needs one run of '#' in its file name for the frame's index")
    missing, incomplete = [], []
    for frame in range(first, last + 1):
        path = frame_path(args.out, frame)
        if not os.path.exists(path):
            missing.append(frame)
        elif not frame_complete(path):
            incomplete.append(frame)
    total = last - first + 1
    if not missing and not incomplete:
        print("all %d frames %d..%d are complete" % (total, first, last))
        return 0
    for frame in missing:
        print("missing     %s" % frame_path(args.out, frame))
    for frame in incomplete:
        print("incomplete  %s" % frame_path(args.out, frame))
    print("%d of %d frames to render again" % (len(missing) + len(incomplete), total))
    if args.per_task:
        tasks = sorted({(frame - first) // args.per_task for frame in missing + incomplete})
        print("requeue: sbatch --array=%s tools/slurm/memograph_array.sbatch render %d:%d %d -- ..."
              % (",".join(str(t) for t in tasks), first, last, args.per_task))
        print("tasks: %s" % " ".join(str(t) for t in tasks))
    return 1


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
