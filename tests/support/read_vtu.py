#!/usr/bin/env python3
"""Reads a binary .vtu file (UnstructuredGrid, appended raw data, zlib blocks with UInt64 headers) with the
Python standard library only, checks its structure, and prints every array as text for the C++ tests:

    piece <NumberOfPoints> <NumberOfCells>
    PointData <attribute>=<value> ...
    CellData <attribute>=<value> ...
    array <Name, or Points for the coordinates> <NumberOfComponents> <number of values>
    <values separated by spaces>

Exits with status 1 and a message on stderr when the file breaks the format."""
import struct
import sys
import xml.etree.ElementTree as ET
import zlib

TYPES = {"Float64": "d", "Float32": "f", "Int64": "q", "Int32": "i", "UInt8": "B", "UInt64": "Q"}


def fail(msg):
    sys.stderr.write("read_vtu: " + msg + "\n")
    sys.exit(1)


def read(path):
    data = open(path, "rb").read()
    marker = data.find(b"<AppendedData")
    if marker < 0:
        fail("no <AppendedData>")
    start = data.index(b"_", marker) + 1
    head = data[:marker] + b"</VTKFile>"
    root = ET.fromstring(head)
    appended = ET.fromstring(data[marker:data.index(b">", marker) + 1].rstrip(b">") + b"/>")
    if appended.get("encoding") != "raw":
        fail("appended data not raw")
    expect = {"type": "UnstructuredGrid", "byte_order": "LittleEndian", "header_type": "UInt64",
              "compressor": "vtkZLibDataCompressor"}
    for k, v in expect.items():
        if root.tag != "VTKFile" or root.get(k) != v:
            fail("VTKFile %s is %r, expected %r" % (k, root.get(k), v))
    position = start  # arrays must follow each other without gaps, in document order
    pieces = []
    for piece in root.iter("Piece"):
        npts, ncells = int(piece.get("NumberOfPoints")), int(piece.get("NumberOfCells"))
        out = {"points": npts, "cells": ncells, "tags": {}, "arrays": []}
        for section in ("PointData", "CellData", "Points", "Cells"):
            node = piece.find(section)
            if node is None:
                fail("piece without <%s>" % section)
            out["tags"][section] = dict(node.attrib)
            for a in node.findall("DataArray"):
                if a.get("format") != "appended":
                    fail("DataArray not appended")
                offset = int(a.get("offset"))
                if start + offset != position:
                    fail("array %s at offset %d, expected %d" % (a.get("Name"), offset, position - start))
                nblocks, block, last = struct.unpack_from("<3Q", data, position)
                sizes = struct.unpack_from("<%dQ" % nblocks, data, position + 24)
                position += 24 + 8 * nblocks
                raw = b""
                for b, size in enumerate(sizes):
                    chunk = zlib.decompress(data[position:position + size])
                    position += size
                    want = last if (b == nblocks - 1 and last) else block
                    if len(chunk) != want:
                        fail("block %d holds %d bytes, header says %d" % (b, len(chunk), want))
                    raw += chunk
                fmt = TYPES[a.get("type")]
                n = len(raw) // struct.calcsize(fmt)
                values = struct.unpack("<%d%s" % (n, fmt), raw)
                comps = int(a.get("NumberOfComponents", "1"))
                name = a.get("Name") or section
                tuples = {"PointData": npts, "Points": npts, "CellData": ncells}.get(section)
                if name in ("offsets", "types"):
                    tuples = ncells
                if tuples is not None and n != tuples * comps:
                    fail("array %s has %d values, expected %d x %d" % (name, n, tuples, comps))
                out["arrays"].append((name, comps, values))
        arrays = {name: values for name, _, values in out["arrays"]}
        offsets = arrays.get("offsets", ())
        if len(arrays.get("connectivity", ())) != (offsets[-1] if offsets else 0):
            fail("connectivity length differs from the last offset")
        if any(not 0 <= c < npts for c in arrays.get("connectivity", ())):
            fail("connectivity refers to a point outside the piece")
        pieces.append(out)
    if data[position:].split() != [b"</AppendedData>", b"</VTKFile>"]:
        fail("unexpected bytes after the last array")
    return pieces


def main():
    for p in read(sys.argv[1]):
        print("piece", p["points"], p["cells"])
        for section in ("PointData", "CellData"):
            print(section, " ".join("%s=%s" % kv for kv in p["tags"][section].items()))
        for name, comps, values in p["arrays"]:
            print("array", name, comps, len(values))
            print(" ".join(repr(v) for v in values))


if __name__ == "__main__":
    main()
