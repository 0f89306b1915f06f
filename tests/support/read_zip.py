#!/usr/bin/env python3
"""Reads a ZIP archive with Python's zipfile: checks every entry's CRC and prints {name: text} as JSON for the
C++ tests. Exits with status 1 and a message on stderr when the archive is broken."""
import json
import sys
import zipfile

try:
    with zipfile.ZipFile(sys.argv[1]) as z:
        bad = z.testzip()
        if bad is not None:
            sys.exit("read_zip: CRC mismatch in " + bad)
        json.dump({name: z.read(name).decode("utf-8") for name in z.namelist()}, sys.stdout)
except zipfile.BadZipFile as e:
    sys.exit("read_zip: " + str(e))
