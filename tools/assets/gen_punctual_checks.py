#!/usr/bin/env python3
"""Small scenes that check KHR_lights_punctual placement against Blender (issue #60): each light
type on child nodes under rotated, non-uniformly scaled parents, above a sphere and a box on a
grey floor, with a camera. Ranges are beyond the scene except in range_point.gltf, where
Blender (which has no range) must differ. Writes into the folder given (default
build/punctual-checks): spot_child.gltf, point_child.gltf, sun_child.gltf, range_point.gltf.
The fidelity harness renders them with Penumbra and Cycles (tools/fidelity --models-dir)."""
import math
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from gltf_builder import GltfBuilder, MeshData, quat_axis_angle, quat_look  # noqa: E402


def quat_mul(a, b):
    ax, ay, az, aw = a
    bx, by, bz, bw = b
    return (aw * bx + ax * bw + ay * bz - az * by, aw * by - ax * bz + ay * bw + az * bx,
            aw * bz + ax * by - ay * bx + az * bw, aw * bw - ax * bx - ay * by - az * bz)


def scene(name, light, rig, out_dir):
    """`light`: the KHR_lights_punctual light; `rig`: (parent TRS, child TRS) of its nodes."""
    b = GltfBuilder(name)
    floor = MeshData()
    floor.quad((-4, 0, 4), (4, 0, 4), (4, 0, -4), (-4, 0, -4), (0, 1, 0))
    ball = MeshData()
    ball.uv_sphere((-0.8, 0.5, 0), 0.5, 48, 24)
    box = MeshData()
    box.box((0.4, 0.0, -0.4), (1.2, 0.8, 0.4))
    grey = b.material("grey", (0.7, 0.7, 0.7), roughness=0.7)
    nodes = [b.node(n, mesh=b.mesh(n, [b.primitive(m, grey)]))
             for n, m in (("floor", floor), ("ball", ball), ("box", box))]
    (pt, pr, ps), (ct, cr) = rig
    child = b.node("light", translation=ct, rotation=cr,
                   extensions={"KHR_lights_punctual": {"light": 0}})
    nodes.append(b.node("rig", translation=pt, rotation=pr, scale_=ps, children=[child]))
    cam = b.camera("view", 0.75, 4.0 / 3.0, 0.05, 100.0)
    eye = (0.0, 4.5, 6.5)
    nodes.append(b.node("view", camera=cam, translation=eye, rotation=quat_look(eye, (0, 0.3, 0))))
    b.scene(name, nodes)
    b.ext_used.add("KHR_lights_punctual")
    finish = b._finish

    def with_lights(uri):
        doc = finish(uri)
        doc.setdefault("extensions", {})["KHR_lights_punctual"] = {"lights": [light]}
        return doc

    b._finish = with_lights
    b.write_gltf(os.path.join(out_dir, name + ".gltf"))


def main():
    out_dir = sys.argv[1] if len(sys.argv) > 1 else "build/punctual-checks"
    os.makedirs(out_dir, exist_ok=True)
    down = quat_axis_angle((1, 0, 0), -math.pi / 2)  # local -Z to world -Y
    turn = quat_axis_angle((0, 1, 0), 0.6)
    # Spot: the parent turned about +Y and scaled unevenly, the child turned down and tilted.
    tilt = quat_mul(quat_axis_angle((0, 0, 1), 0.35), down)
    scene("spot_child", {"type": "spot", "intensity": 60, "range": 100,
                         "spot": {"innerConeAngle": 0.35, "outerConeAngle": 0.6}},
          (((0.3, 3.0, 0.2), turn, (2.0, 1.0, 0.5)), ((0.0, 0.0, 0.0), tilt)), out_dir)
    # Point: offset inside a scaled parent (a point light's position scales, its light does not).
    scene("point_child", {"type": "point", "intensity": 30, "range": 100, "color": [1.0, 0.9, 0.8]},
          (((0.0, 1.0, 0.0), turn, (2.0, 1.0, 0.5)), ((0.2, 1.5, 1.0), (0, 0, 0, 1))), out_dir)
    # Directional: the direction from both rotations (the position is irrelevant).
    slant = quat_mul(quat_axis_angle((1, 0, 0), -0.9), quat_axis_angle((0, 1, 0), 0.0))
    scene("sun_child", {"type": "directional", "intensity": 3},
          (((5.0, 5.0, 5.0), turn, (1.0, 3.0, 1.0)), ((0.0, 0.0, 0.0), slant)), out_dir)
    # Range: the light reaches 2.5 m, so the floor's far side is dark in Penumbra (glTF's range
    # window) and lit in Blender, which has no range: a known difference, not a bug.
    scene("range_point", {"type": "point", "intensity": 30, "range": 2.5},
          (((0.0, 1.5, 0.0), (0, 0, 0, 1), (1.0, 1.0, 1.0)), ((0.0, 0.0, 0.0), (0, 0, 0, 1))), out_dir)


def write_catalog(out_dir):
    """A CATALOG.tsv in the fidelity harness's format (tools/fidelity --assets OUT_DIR)."""
    cols = ["name", "category", "main_file", "source_repo", "source_path", "source_commit",
            "license", "size_bytes", "extensionsUsed", "features", "triangles", "primitives",
            "nodes", "validator_errors", "validator_warnings", "notes"]
    rows = []
    for name in ("spot_child", "point_child", "sun_child", "range_point"):
        os.makedirs(os.path.join(out_dir, name), exist_ok=True)
        for ext in (".gltf", ".bin"):
            os.replace(os.path.join(out_dir, name + ext), os.path.join(out_dir, name, name + ext))
        rows.append([name, "punctual-check", name + "/" + name + ".gltf", "penumbra",
                     "tools/assets/gen_punctual_checks.py", "-", "CC0-1.0 (generated)", "0",
                     "KHR_lights_punctual", "gltf,punctual", "0", "3", "6", "0", "0",
                     "Blender has no range" if name == "range_point" else "-"])
    with open(os.path.join(out_dir, "CATALOG.tsv"), "w", encoding="utf-8", newline="\n") as f:
        f.write("\t".join(cols) + "\n")
        for r in rows:
            f.write("\t".join(r) + "\n")


if __name__ == "__main__":
    main()
    write_catalog(sys.argv[1] if len(sys.argv) > 1 else "build/punctual-checks")
