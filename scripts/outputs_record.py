"""outputs.json for a folder whose rows.csv a script writes (harness/output/outputs_record.h):
the file's FNV-1a 64 digest, so that `relieflab verify` tells an edited rows.csv from the one
the script wrote. Called by the producing scripts right after they write the file:
    python3 scripts/outputs_record.py FOLDER rows.csv [FILE ...]"""
import json
import os
import sys


def fnv1a64(data: bytes) -> str:
    h = 0xCBF29CE484222325
    for byte in data:
        h = ((h ^ byte) * 0x100000001B3) & 0xFFFFFFFFFFFFFFFF
    return f"fnv1a64:{h:016x}"


def write_record(folder, names):
    files = {}
    for name in sorted(names):
        with open(os.path.join(folder, name), "rb") as f:
            files[name] = fnv1a64(f.read())
    record = {"about": "the files relieflab wrote here, with the digests of their contents "
                       "(FNV-1a, 64 bits): relieflab verify refuses a folder whose files differ "
                       "from them",
              "files": files}
    path = os.path.join(folder, "outputs.json")
    with open(path + ".tmp", "w") as f:
        f.write(json.dumps(record, indent=2) + "\n")
    os.replace(path + ".tmp", path)


if __name__ == "__main__":
    if len(sys.argv) < 3:
        sys.exit(__doc__)
    write_record(sys.argv[1], sys.argv[2:])
