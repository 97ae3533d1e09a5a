#!/usr/bin/env python3
"""Dense mesh (> 100k triangles) for load / throughput tests, as a .glb.

Writes assets/dense/dense.glb (or --out-dir): a procedurally displaced UV
sphere ("rock", 256 x 224 segments = 114,176 triangles, 57,825 vertices, so
uint16 indices still suffice) resting on a floor quad, with a camera "dense".
No UVs (saves ~0.46 MB); smooth normals from area-weighted face normals, with
the u-seam and the poles welded so shading has no visible seam. ~2.1 MB.

Displacement: r = R * (1 + sum_k a_k sin(f_k (d_k . n) + phase_k)) over unit
directions n, with 24 waves whose directions, frequencies and phases come from
a fixed-seed linear congruential generator (our own, so the output cannot
change with the Python version). Metres, +Y up, lit by the environment.
"""
import math
import sys

import gltf_builder as gb

RADIUS = 0.5
SEG_U, SEG_V = 256, 224
WAVES = 24


def waves():
    rng = gb.Lcg(20240611)
    out = []
    for k in range(WAVES):
        z = 2.0 * rng.next() - 1.0
        a = 2.0 * math.pi * rng.next()
        s = math.sqrt(1.0 - z * z)
        freq = 2.5 * (1.15 ** k)                 # 2.5 .. ~62 rad per unit direction
        amp = 0.07 * (0.87 ** k)                 # finer waves are weaker
        out.append(((s * math.cos(a), z, s * math.sin(a)), freq, amp, 2 * math.pi * rng.next()))
    return out


def rock():
    m = gb.MeshData()
    m.uv_sphere((0.0, 0.0, 0.0), 1.0, SEG_U, SEG_V)   # unit directions in m.pos
    wv = waves()
    for k, n in enumerate(m.pos):
        d = sum(amp * math.sin(freq * gb.dot(dirn, n) + ph) for dirn, freq, amp, ph in wv)
        m.pos[k] = gb.scale(n, RADIUS * (1.0 + d))
    # Smooth normals; seam column i == SEG_U and the pole rows share one slot.
    row = SEG_U + 1

    def slot(v):
        j, i = divmod(v, row)
        if j == 0:
            return 0
        if j == SEG_V:
            return SEG_V * row
        return j * row + (0 if i == SEG_U else i)
    acc = [[0.0, 0.0, 0.0] for _ in m.pos]
    pos, idx = m.pos, m.idx
    for t in range(0, len(idx), 3):
        a, b, c = pos[idx[t]], pos[idx[t + 1]], pos[idx[t + 2]]
        fn = gb.cross(gb.sub(b, a), gb.sub(c, a))      # length = 2 x area: area weighting
        for v in idx[t:t + 3]:
            s = acc[slot(v)]
            s[0] += fn[0]
            s[1] += fn[1]
            s[2] += fn[2]
    m.nrm = [gb.normalize(acc[slot(v)]) for v in range(len(pos))]
    return m


def main(argv):
    path = gb.out_path(argv, gb.repo_assets("dense"), "dense.glb")
    b = gb.GltfBuilder("Penumbra tools/assets/gen_dense.py")
    rk = rock()
    lift = -min(p[1] for p in rk.pos)
    stone = b.material("rock", (0.70, 0.35, 0.25), roughness=0.6)
    nodes = [b.node("rock", mesh=b.mesh("rock", [b.primitive(rk, stone, uvs=False)]),
                    translation=(0.0, lift, 0.0))]
    floor = gb.MeshData()
    h = 10.0
    floor.quad((-h, 0.0, h), (h, 0.0, h), (h, 0.0, -h), (-h, 0.0, -h), (0.0, 1.0, 0.0))
    ground = b.material("floor", (0.6, 0.6, 0.6), roughness=0.8)
    nodes.append(b.node("floor", mesh=b.mesh("floor", [b.primitive(floor, ground, uvs=False)])))
    eye, target = (0.0, 1.0, 2.8), (0.0, lift * 0.9, 0.0)
    cam = b.camera("dense", math.radians(35.0), 16.0 / 9.0, 0.05, 50.0)
    nodes.append(b.node("dense", camera=cam, translation=eye, rotation=gb.quat_look(eye, target)))
    b.scene("dense", nodes)
    b.write_glb(path)
    print("wrote", path)


if __name__ == "__main__":
    main(sys.argv[1:])
