#!/usr/bin/env python3
"""A real textured model for the convergence benchmark (issue #36): Cesium's milk truck.

Not a committed asset: it is converted on demand from Debian's `assimp-testmodels` (the glTF
1.0 sample `CesiumMilkTruck`, Cesium, CC-BY 4.0), which `tools/setup` installs with
`assimp-utils`. `assimp export ... -fglb2` writes it as glTF 2.0 (a .glb that references the
923 KB texture atlas beside it; the wheels are instanced nodes). Beside them goes
`milk_truck.json`: the model under the studio sky (assets/env/studio_sky.hdr, its sun
included) at 640x360, the size issue #36 asks for, seen through a camera added to the .glb (a
three-quarter view whose bounding sphere fills the height): an A/B of two revisions
(tools/ab-bench) must shade the same pixels on both sides, and the default framing is code
that changes between revisions.

  tools/assets/gen_milk_truck.py [--out-dir DIR]     (default: build/real-models/milk_truck)

Exits 1 with one line when the package or the converter is missing.
"""
import argparse
import json
import math
import os
import shutil
import struct
import subprocess
import sys

from check_gltf import Checker

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
SOURCE = '/usr/share/assimp/models/glTF/CesiumMilkTruck'


def _quaternion(right, up, back):  # of the rotation whose columns are the three axes
    m00, m11, m22 = right[0], up[1], back[2]
    tr = m00 + m11 + m22
    if tr > 0:
        s = 2 * math.sqrt(tr + 1)
        return [(up[2] - back[1]) / s, (back[0] - right[2]) / s, (right[1] - up[0]) / s, s / 4]
    if m00 > m11 and m00 > m22:
        s = 2 * math.sqrt(1 + m00 - m11 - m22)
        return [s / 4, (up[0] + right[1]) / s, (back[0] + right[2]) / s, (up[2] - back[1]) / s]
    if m11 > m22:
        s = 2 * math.sqrt(1 + m11 - m00 - m22)
        return [(up[0] + right[1]) / s, s / 4, (back[1] + up[2]) / s, (back[0] - right[2]) / s]
    s = 2 * math.sqrt(1 + m22 - m00 - m11)
    return [(back[0] + right[2]) / s, (back[1] + up[2]) / s, s / 4, (right[1] - up[0]) / s]


def add_camera(glb_path, aspect):
    """A perspective camera in the .glb: a three-quarter view from the front right and a little
    above, at the distance where the bounding sphere fills the vertical field of view."""
    data = open(glb_path, 'rb').read()
    json_len = struct.unpack_from('<I', data, 12)[0]
    doc = json.loads(data[20:20 + json_len])
    rest = data[20 + json_len:]
    checker = Checker(glb_path)
    checker.doc = doc
    checker.world_matrices()
    lo, hi = checker.bounds()
    centre = [(a + b) / 2 for a, b in zip(lo, hi)]
    radius = math.dist(lo, hi) / 2
    yfov = 0.6
    d = [1.0, 0.45, 1.3]
    n = math.sqrt(sum(x * x for x in d))
    back = [x / n for x in d]
    dist = radius / math.sin(yfov / 2)
    right = [back[2], 0.0, -back[0]]
    rn = math.sqrt(sum(x * x for x in right))
    right = [x / rn for x in right]
    up = [back[1] * right[2] - back[2] * right[1], back[2] * right[0] - back[0] * right[2],
          back[0] * right[1] - back[1] * right[0]]
    doc.setdefault('cameras', []).append(
        {'type': 'perspective', 'name': 'benchmark',
         'perspective': {'yfov': yfov, 'aspectRatio': aspect, 'znear': radius / 100}})
    doc['nodes'].append({'name': 'benchmark camera', 'camera': len(doc['cameras']) - 1,
                         'translation': [c + dist * b for c, b in zip(centre, back)],
                         'rotation': _quaternion(right, up, back)})
    doc['scenes'][doc.get('scene', 0)]['nodes'].append(len(doc['nodes']) - 1)
    text = json.dumps(doc).encode()
    text += b' ' * (-len(text) % 4)
    body = struct.pack('<II', len(text), 0x4E4F534A) + text + rest
    with open(glb_path, 'wb') as f:
        f.write(struct.pack('<III', 0x46546C67, 2, 12 + len(body)) + body)


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument('--out-dir', default=os.path.join(ROOT, 'build', 'real-models', 'milk_truck'))
    a = ap.parse_args()
    gltf = os.path.join(SOURCE, 'CesiumMilkTruck.gltf')
    if not os.path.isfile(gltf):
        sys.exit('gen_milk_truck: %s is missing: install Debian\'s assimp-testmodels '
                 '(tools/setup does)' % gltf)
    if shutil.which('assimp') is None:
        sys.exit('gen_milk_truck: the assimp command is missing: install Debian\'s assimp-utils '
                 '(tools/setup does)')
    os.makedirs(a.out_dir, exist_ok=True)
    glb = os.path.join(a.out_dir, 'milk_truck.glb')
    done = subprocess.run(['assimp', 'export', gltf, glb, '-fglb2'], capture_output=True,
                          text=True)
    if done.returncode != 0 or not os.path.isfile(glb):
        sys.exit('gen_milk_truck: assimp export failed: %s' %
                 (done.stderr.strip().splitlines() or ['no output'])[-1])
    add_camera(glb, 640 / 360)
    shutil.copyfile(os.path.join(SOURCE, 'CesiumMilkTruck.png'),
                    os.path.join(a.out_dir, 'CesiumMilkTruck.png'))
    scene = {
        'comment': 'Cesium milk truck (CC-BY 4.0), from Debian assimp-testmodels, under the '
                   'studio sky: a real textured model for the convergence benchmark.',
        'gltf': 'milk_truck.glb',
        'environment': {'file': os.path.join(ROOT, 'assets', 'env', 'studio_sky.hdr')},
        'resolution': [640, 360],
        'camera': 'benchmark',
    }
    with open(os.path.join(a.out_dir, 'milk_truck.json'), 'w') as f:
        json.dump(scene, f, indent=2)
        f.write('\n')
    print('wrote %s' % os.path.join(a.out_dir, 'milk_truck.json'))


if __name__ == '__main__':
    main()
