#!/usr/bin/env python3
"""Writes the triangles of a single-geometry COLLADA file (MeshLab export, <triangles> with a
VERTEX input) as binary STL, coordinates unchanged.

rviz draws an .stl in the URDF <material> colour but a .dae in the mesh's own material, so the
propellers are shipped as STL made from RotorS' propeller_cw/ccw.dae:
    dae_to_stl.py meshes/propeller_cw.dae meshes/propeller_cw.stl
"""

import struct
import sys
import xml.etree.ElementTree as ET

import numpy as np

NS = {"c": "http://www.collada.org/2005/11/COLLADASchema"}


def read_triangles(path):
    """(n, 3, 3) array of triangle corners [m] of the file's one <triangles> element."""
    root = ET.parse(path).getroot()
    mesh = root.find(".//c:geometry/c:mesh", NS)
    if mesh is None:
        raise SystemExit(f"{path}: no <geometry><mesh> element")
    vertices_source = mesh.find("c:vertices/c:input[@semantic='POSITION']", NS).get("source").lstrip("#")
    positions = mesh.find(f"c:source[@id='{vertices_source}']/c:float_array", NS)
    xyz = np.array(positions.text.split(), dtype=float).reshape(-1, 3)
    triangles = mesh.find("c:triangles", NS)
    if triangles is None:
        raise SystemExit(f"{path}: no <triangles> element (polylists are not supported)")
    inputs = triangles.findall("c:input", NS)
    stride = max(int(i.get("offset")) for i in inputs) + 1
    vertex_offset = next(int(i.get("offset")) for i in inputs if i.get("semantic") == "VERTEX")
    p = np.array(triangles.find("c:p", NS).text.split(), dtype=int).reshape(-1, stride)
    return xyz[p[:, vertex_offset]].reshape(-1, 3, 3)


def write_stl(path, corners):
    normals = np.cross(corners[:, 1] - corners[:, 0], corners[:, 2] - corners[:, 0])
    normals /= np.maximum(np.linalg.norm(normals, axis=1, keepdims=True), 1e-12)
    with open(path, "wb") as f:
        f.write(b"binary STL from a COLLADA file by dae_to_stl.py".ljust(80, b" "))
        f.write(struct.pack("<I", len(corners)))
        for n, c in zip(normals, corners):
            f.write(struct.pack("<12fH", *n, *c.ravel(), 0))


if __name__ == "__main__":
    if len(sys.argv) != 3:
        raise SystemExit("usage: dae_to_stl.py IN.dae OUT.stl")
    corners = read_triangles(sys.argv[1])
    write_stl(sys.argv[2], corners)
    print(f"{sys.argv[2]}: {len(corners)} triangles")
