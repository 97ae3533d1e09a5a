// The hand-off page's mapping of EXT_lights_area to three-gpu-pathtracer's area lights
// (web/handoff/pathtracer.mjs), in node with three.js alone: sizes, radiance, which side emits,
// disks, lamp proxies; the tone mappers; the background.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import * as THREE from 'three';
import { TONE_MAPPERS, addAreaLights, backgroundFor } from '../handoff/pathtracer.mjs';

// A glTF as three's GLTFLoader hands it over: the JSON and the node objects.
function fakeGltf(json) {
  const scene = new THREE.Group();
  const objects = json.nodes.map((n) => {
    const o = new THREE.Object3D();
    if (n.translation) o.position.fromArray(n.translation);
    if (n.rotation) o.quaternion.fromArray(n.rotation);
    if (n.scale) o.scale.fromArray(n.scale);
    scene.add(o);
    return o;
  });
  return { scene, parser: { json, getDependency: async (kind, i) => objects[i] } };
}

const close = (a, b, what, eps = 1e-6) => assert.ok(Math.abs(a - b) <= eps, `${what}: ${a} vs ${b}`);

test('EXT_lights_area rect and disk lights become area lights of the same radiance, size and side', async () => {
  const s = Math.SQRT1_2;
  const gltf = fakeGltf({
    extensions: { EXT_lights_area: { lights: [
      { type: 'rect', color: [1, 0.5, 0.25], intensity: 17, size: 0.1, rect: { aspect: 2 } },
      { type: 'disk', intensity: 50, size: 0.4 },
    ] } },
    nodes: [
      // Facing down (local -Z to world -Y), scaled 3 on its largest axis.
      { rotation: [-s, 0, 0, s], translation: [1, 2, 3], scale: [3, 2, 1],
        extensions: { EXT_lights_area: { light: 0 } } },
      { translation: [0, 1, 0], extensions: { EXT_lights_area: { light: 1 } } },
      { extras: { area_light_proxy: 0 } },
      { extras: { area_light_proxy: 7 } },  // names no light: kept
    ],
  });
  const proxy = await gltf.parser.getDependency('node', 2);
  const stray = await gltf.parser.getDependency('node', 3);
  const proxies = [];
  assert.equal(await addAreaLights(gltf, proxies), 2);
  const lights = [];
  gltf.scene.traverse((o) => { if (o.isRectAreaLight) lights.push(o); });
  assert.equal(lights.length, 2);
  const [rect, disk] = lights;

  // Radiance: the path tracer emits color x intensity; the colour is linear.
  assert.equal(rect.intensity, 17);
  close(rect.color.r, 1, 'r'); close(rect.color.g, 0.5, 'g'); close(rect.color.b, 0.25, 'b');
  // Size in world units: height = scale x size, width = height x aspect.
  close(rect.height, 0.3, 'rect height');
  close(rect.width, 0.6, 'rect width');
  assert.equal(rect.isCircular, false);
  // As three-gpu-pathtracer packs it (LightsInfoUniformStruct): u = width along the light's X,
  // v = height along its Y, both by its world rotation; it emits toward -(u x v).
  const q = rect.getWorldQuaternion(new THREE.Quaternion());
  const u = new THREE.Vector3(rect.width, 0, 0).applyQuaternion(q);
  const v = new THREE.Vector3(0, rect.height, 0).applyQuaternion(q);
  close(u.length(), 0.6, '|u|'); close(v.length(), 0.3, '|v|');
  const emits = u.clone().cross(v).normalize().negate();
  close(emits.y, -1, 'emits down (the node\'s local -Z)');
  const p = rect.getWorldPosition(new THREE.Vector3());
  close(p.x, 1, 'x'); close(p.y, 2, 'y'); close(p.z, 3, 'z');

  // A disk: circular, width = height = diameter.
  assert.equal(disk.isCircular, true);
  close(disk.width, 0.4, 'disk width'); close(disk.height, 0.4, 'disk height');
  assert.equal(disk.intensity, 50);
  close(disk.color.r, 1, 'default colour');

  // The lamp proxy of light 0 leaves the path-traced scene (for the lamp layer); a node naming
  // no light stays.
  assert.equal(proxy.parent, null);
  assert.deepEqual(proxies, [proxy]);
  assert.equal(stray.parent, gltf.scene);
});

test('every Penumbra tone mapper has a three.js one; PBR Neutral is NeutralToneMapping', () => {
  assert.deepEqual(Object.keys(TONE_MAPPERS).sort(), ['aces', 'none', 'pbr-neutral', 'reinhard']);
  assert.equal(TONE_MAPPERS['pbr-neutral'], THREE.NeutralToneMapping);
});

test('the background: none over a transparent background, the environment where shown, else black', () => {
  const env = new THREE.Texture();
  assert.equal(backgroundFor({}, env), env);
  assert.equal(backgroundFor({ showBackground: true, transparentBackground: false }, env), env);
  assert.equal(backgroundFor({ transparentBackground: true }, env), null);
  assert.equal(backgroundFor({ transparentBackground: true, showBackground: false }, null), null);
  const black = backgroundFor({ showBackground: false }, env);
  assert.ok(black.isColor && black.r === 0 && black.g === 0 && black.b === 0);
  assert.ok(backgroundFor({}, null).isColor, 'no environment: black');
});
