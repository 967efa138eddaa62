"""Writes the RECORD of the installed package ccal: the list of its installed files with their SHA-256 (base64
URL-safe, unpadded) and size, in the format of the Python packaging specifications (which pip reads to
uninstall a package). Run by `cmake --install` (python/CMakeLists.txt):

    python3 python/write_record.py SITE_FOLDER ccal-VERSION.dist-info
"""

import base64
import hashlib
import os
import sys


def record_rows(site, dist_info):
    rows = []
    for folder in ("ccal", dist_info):
        for name in sorted(os.listdir(os.path.join(site, folder))):
            path = os.path.join(site, folder, name)
            if name == "RECORD" or not os.path.isfile(path):  # RECORD lists itself without a hash
                continue
            with open(path, "rb") as f:
                data = f.read()
            digest = base64.urlsafe_b64encode(hashlib.sha256(data).digest()).rstrip(b"=").decode()
            rows.append(f"{folder}/{name},sha256={digest},{len(data)}")
    rows.append(f"{dist_info}/RECORD,,")
    return rows


if __name__ == "__main__":
    site, dist_info = sys.argv[1:3]
    with open(os.path.join(site, dist_info, "RECORD"), "w", encoding="utf-8", newline="\n") as f:
        f.write("\n".join(record_rows(site, dist_info)) + "\n")
