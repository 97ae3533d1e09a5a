#!/usr/bin/env python3
"""A real textured model for the convergence benchmark (issue #36): Cesium's milk truck.

Not a committed asset: it is converted on demand from Debian's `assimp-testmodels` (the glTF
1.0 sample `CesiumMilkTruck`, Cesium, CC-BY 4.0), which `tools/setup` installs with
`assimp-utils`. `assimp export ... -fglb2` writes it as glTF 2.0 (a .glb that references the
923 KB texture atlas beside it; the wheels are instanced nodes). Beside them goes
`milk_truck.json`: the model under the studio sky (assets/env/studio_sky.hdr, its sun
included) at 640x360, the size issue #36 asks for.

  tools/assets/gen_milk_truck.py [--out-dir DIR]     (default: build/real-models/milk_truck)

Exits 1 with one line when the package or the converter is missing.
"""
import argparse
import json
import os
import shutil
import subprocess
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
SOURCE = '/usr/share/assimp/models/glTF/CesiumMilkTruck'


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
    shutil.copyfile(os.path.join(SOURCE, 'CesiumMilkTruck.png'),
                    os.path.join(a.out_dir, 'CesiumMilkTruck.png'))
    scene = {
        'comment': 'Cesium milk truck (CC-BY 4.0), from Debian assimp-testmodels, under the '
                   'studio sky: a real textured model for the convergence benchmark.',
        'gltf': 'milk_truck.glb',
        'environment': {'file': os.path.join(ROOT, 'assets', 'env', 'studio_sky.hdr')},
        'resolution': [640, 360],
    }
    with open(os.path.join(a.out_dir, 'milk_truck.json'), 'w') as f:
        json.dump(scene, f, indent=2)
        f.write('\n')
    print('wrote %s' % os.path.join(a.out_dir, 'milk_truck.json'))


if __name__ == '__main__':
    main()
