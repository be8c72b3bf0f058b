"""What a folder holds, to check that a failed command left it as it was (outputs are
all-or-nothing): every path below it mapped to its file's SHA-256, or 'dir' for a folder,
a link or anything else that is not a regular file."""
import hashlib
import os


def snapshot(folder):
    state = {}
    for root, dirs, files in os.walk(folder):
        for name in dirs + files:
            path = os.path.join(root, name)
            rel = os.path.relpath(path, folder)
            if os.path.isfile(path) and not os.path.islink(path):
                with open(path, "rb") as f:
                    state[rel] = hashlib.sha256(f.read()).hexdigest()
            else:
                state[rel] = "dir"
    return state
