#!/usr/bin/env bash
# The readers of EXT_lights_area outside the renderer (issue #61) know every area-light shape of
# the renderer's light table: each declares AREA_SHAPES, compared here with the area rows of
# renderer/src/scene/light_kinds.cpp (docs/architecture.md, "Recipe: a new area-light shape").
# Usage: light_readers.sh <dir of libpenumbra.a> <build dir> (both unused)
set -uo pipefail
ROOT="$(cd "$(dirname "$0")/../.." && pwd)"
python3 - "$ROOT" <<'PY'
import re, sys
root = sys.argv[1]
table = open(root + '/renderer/src/scene/light_kinds.cpp').read()
shapes = re.findall(r'\{LightType::\w+, "(\w+)", true,', table)
if len(shapes) < 2:
    sys.exit('FAIL: no area rows found in light_kinds.cpp (the test reads "{LightType::X, "name", true,")')
status = 0
for reader in ['web/handoff/pathtracer.mjs', 'tools/reference/blender_scene.py',
               'tools/assets/check_gltf.py', 'tools/assets/preview_gltf.py']:
    text = open(root + '/' + reader).read()
    m = re.search(r"AREA_SHAPES = [\[(]([^\])]*)[\])]", text)
    if not m:
        print('FAIL: %s declares no AREA_SHAPES' % reader)
        status = 1
        continue
    known = re.findall(r"'(\w+)'", m.group(1))
    missing = [s for s in shapes if s not in known]
    unknown = [s for s in known if s not in shapes]
    if missing or unknown:
        print('FAIL: %s: AREA_SHAPES %s; the light table has %s' % (reader, known, shapes))
        status = 1
    else:
        print('ok: %s knows %s' % (reader, ', '.join(shapes)))
sys.exit(status)
PY
