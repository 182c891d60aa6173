// engines/web/three_page.js — the three.js harness, in the page: loads a pack scene with three.js's
// own GLTFLoader and renders one mask per light with three.js's own shadow maps, with the variant's
// settings, on one of three backends: `webgl2`, WebGLRenderer (WebGLShadowMap; three.html, where
// 'three' is three.module.js); `webgpu`, WebGPURenderer on WebGPU (ShadowNode); `webgpu-webgl2`,
// WebGPURenderer's own WebGL2 backend (forceWebGL; both on three_webgpu.html, where 'three' is
// three.webgpu.js). engines/README.md says what is adapted and why.
import * as THREE from 'three';
import { GLTFLoader } from 'three/addons/loaders/GLTFLoader.js';
import { turnedAway, combine, base64, packCamera, packLights, withEnvironment, adapterText, webglAdapterText,
  browserText, halfZToGl, cubeFacesInOrder } from './common.js';

// three.js's defaults (src/lights/LightShadow.js): mapSize 512, bias 0, normalBias 0, radius 1; the
// renderer's shadowMap.type is PCFShadowMap. "Recommended" is what three.js's own documentation
// of LightShadow suggests against artefacts: a larger map ("higher values give better quality
// shadows") and a bias "in the order of 0.0001" (negative: it moves the receiver toward the light,
// `shadowCoord.z += shadowBias` in shadowmap_pars_fragment). A control changes one setting of the
// variant it names.
const VARIANTS = {
  basic: { type: THREE.BasicShadowMap, technique: 'shadowmap' },
  pcf: { type: THREE.PCFShadowMap, technique: 'shadowmap-pcf' },
  'pcf-recommended': { type: THREE.PCFShadowMap, technique: 'shadowmap-pcf', mapSize: 2048, bias: -0.0001 },
  // Variance shadow maps, judged as a filtered hard technique (lit where the term is at least ½):
  // three.js's VSM blurs the moments over `radius` texels, it does not model an area light.
  vsm: { type: THREE.VSMShadowMap, technique: 'shadowmap-pcf' },
  // Controls. pcf-near-fitted: pcf with the point lights' near plane fitted to the scene (half the
  // distance to the nearest triangle) instead of three.js's 0.5. pcf-recommended-no-bias:
  // pcf-recommended with the bias back at 0.
  'pcf-near-fitted': { type: THREE.PCFShadowMap, technique: 'shadowmap-pcf', nearFitted: true },
  'pcf-recommended-no-bias': { type: THREE.PCFShadowMap, technique: 'shadowmap-pcf', mapSize: 2048, bias: 0 },
  // pcf-depth-no-alpha-test: pcf with the alpha test taken out of three.js's depth pass alone (the
  // depth material WebGLShadowMap made for a masked mesh loses its `map` and `alphaTest` just before
  // it draws, in the mesh's onBeforeShadow); the camera's passes keep theirs.
  'pcf-depth-no-alpha-test': { type: THREE.PCFShadowMap, technique: 'shadowmap-pcf', depthAlphaTest: false },
  // pcf-bind-pose: pcf with every skeleton put back in its bind pose (Skeleton.pose, three.js's own),
  // the pack's pose ignored: the skinned scenes' verdicts are the pose's.
  'pcf-bind-pose': { type: THREE.PCFShadowMap, technique: 'shadowmap-pcf', bindPose: true },
  // WebGPURenderer only: cascaded shadow maps for directional lights, three.js's CSMShadowNode
  // (examples/jsm/csm) with its defaults (3 cascades, practical splits, no fade) over the camera's
  // range, PCF in each cascade; other lights as pcf.
  csm: { type: THREE.PCFShadowMap, technique: 'csm-pcf', csm: true },
};

const TYPE_NAMES = { [THREE.BasicShadowMap]: 'BasicShadowMap', [THREE.PCFShadowMap]: 'PCFShadowMap', [THREE.VSMShadowMap]: 'VSMShadowMap' };
const SIDE_NAMES = { [THREE.FrontSide]: 'front', [THREE.BackSide]: 'back', [THREE.DoubleSide]: 'both' };

// three.js's CSMShadowNode, from its examples, for WebGPURenderer (it imports three/webgpu and
// three/tsl, which only three_webgpu.html maps): loaded by init for the WebGPU backends.
let CSMShadowNode = null;

// The page's one renderer and the environment it runs in, made by init(backend) before any scene.
let renderer = null, backend = null, environment = null;

// Makes the renderer the backend asks for and refuses any other: WebGPURenderer falls back to its
// WebGL2 backend when WebGPU is unavailable with one console warning, and a mask drawn so would be
// recorded as WebGPU's. `adapterWanted`, when given, must occur in the adapter's description.
async function init(wanted, adapterWanted, browser) {
  if (wanted === 'webgl2') {
    if (typeof THREE.WebGLRenderer !== 'function') return { error: 'the WebGL2 backend needs three.html (three.module.js)' };
    renderer = new THREE.WebGLRenderer({ antialias: false });
    environment = { api: 'webgl2', adapter: webglAdapterText(renderer.getContext()), engine: `three.js r${THREE.REVISION}` };
  } else if (wanted === 'webgpu' || wanted === 'webgpu-webgl2') {
    if (typeof THREE.WebGPURenderer !== 'function') return { error: `the ${wanted} backend needs three_webgpu.html (three.webgpu.js)` };
    const forceWebGL = wanted === 'webgpu-webgl2';
    ({ CSMShadowNode } = await import('three/addons/csm/CSMShadowNode.js'));
    renderer = new THREE.WebGPURenderer({ antialias: false, forceWebGL });
    await renderer.init();
    const running = renderer.backend.isWebGPUBackend ? 'WebGPU' : renderer.backend.isWebGLBackend ? 'WebGL2' : 'unknown';
    if (running !== (forceWebGL ? 'WebGL2' : 'WebGPU'))
      return { error: `asked for three.js WebGPURenderer on ${forceWebGL ? 'WebGL2' : 'WebGPU'}, but it runs its ${running} backend` +
        `${'gpu' in navigator ? '' : ' (navigator.gpu is missing)'}: no mask written` };
    if (forceWebGL) {
      environment = { api: 'webgl2', adapter: webglAdapterText(renderer.backend.gl), engine: `three.js r${THREE.REVISION} WebGPURenderer` };
    } else {
      const info = renderer.backend.device.adapterInfo;
      if (!info) return { error: 'three.js WebGPURenderer runs on WebGPU, but its device reports no adapter: no mask written' };
      environment = { api: 'webgpu', adapter: adapterText(info), engine: `three.js r${THREE.REVISION}` };
    }
  } else {
    return { error: `no three.js backend "${wanted}" (webgl2, webgpu, webgpu-webgl2)` };
  }
  if (adapterWanted && !environment.adapter.toLowerCase().includes(adapterWanted.toLowerCase()))
    return { error: `asked for the adapter "${adapterWanted}", but three.js runs on "${environment.adapter}": no mask written` };
  environment.browser = browser || browserText();
  backend = wanted;
  renderer.setPixelRatio(1);
  renderer.shadowMap.enabled = true;
  return { environment };
}
const onWebGPU = () => backend !== 'webgl2';  // WebGPURenderer, on either of its backends

// The faces three.js's depth pass draws for a loaded glTF material (FrontSide: glTF's doubleSided
// false): WebGLShadowMap's getDepthMaterial takes material.shadowSide, or else the opposite side
// for Basic and PCF maps and the same side for VSM.
function defaultShadowSide(type, side) {
  if (type === THREE.VSMShadowMap) return side;
  return { [THREE.FrontSide]: THREE.BackSide, [THREE.BackSide]: THREE.FrontSide, [THREE.DoubleSide]: THREE.DoubleSide }[side];
}

// The light three.js renders for pack light `l`, fitted to the scene the way three.js's
// documentation asks of every user (a shadow camera that covers what must be shadowed): the
// directional light's orthographic box around the scene's bounding sphere, a point light's far
// plane beyond the scene (its default, 500, ends inside the largest scene). The point light's near
// plane stays three.js's 0.5 (PointLightShadow) unless the variant fits it too.
// A spot light is the point light at its position, as the other harnesses have it: the mask is
// occlusion everywhere, and a three.js spot shadow covers only its cone.
function engineLight(scene, loaded, l, bounds, meshes, v) {
  const centre = bounds.getCenter(new THREE.Vector3());
  const radius = bounds.getBoundingSphere(new THREE.Sphere()).radius;
  if (l.type === 'directional') {
    const light = loaded;
    scene.attach(light);
    const toward = new THREE.Vector3(...l.homogeneous).normalize();
    light.position.copy(centre).addScaledVector(toward, 2 * radius);
    light.target = new THREE.Object3D();
    light.target.position.copy(centre);
    scene.add(light.target);
    const c = light.shadow.camera;
    Object.assign(c, { left: -radius, right: radius, top: radius, bottom: -radius, near: radius, far: 3 * radius });
    return { light, fit: `orthographic box of the bounding sphere (radius ${radius.toPrecision(6)})` };
  }
  let light = loaded;
  if (l.type === 'spot') {
    light = new THREE.PointLight(0xffffff, 1);
    light.position.set(l.homogeneous[0], l.homogeneous[1], l.homogeneous[2]);
    scene.add(light);
    loaded.visible = false;
  }
  const at = new THREE.Vector3(l.homogeneous[0], l.homogeneous[1], l.homogeneous[2]);
  let far = 0;
  for (const x of [bounds.min.x, bounds.max.x])
    for (const y of [bounds.min.y, bounds.max.y])
      for (const z of [bounds.min.z, bounds.max.z]) far = Math.max(far, at.distanceTo(new THREE.Vector3(x, y, z)));
  light.shadow.camera.far = 1.01 * far;
  if (v.nearFitted) {
    let nearest = Infinity;
    const triangle = new THREE.Triangle(), closest = new THREE.Vector3();
    for (const m of meshes) {
      const p = m.geometry.attributes.position;
      for (let f = 0; f < p.count; f += 3) {
        triangle.setFromAttributeAndIndices(p, f, f + 1, f + 2);
        nearest = Math.min(nearest, triangle.closestPointToPoint(at, closest).distanceTo(at));
      }
    }
    light.shadow.camera.near = 0.5 * nearest;
  }
  return { light, fit: `cube views' far plane ${light.shadow.camera.far.toPrecision(6)}, near ${light.shadow.camera.near.toPrecision(6)}` };
}

// An alpha-masked glTF material (alphaMode MASK): GLTFLoader gives it `alphaTest` = alphaCutoff, the
// mask as `map` and COLOR_0 as vertex colours (`vertexColors`, with alpha when COLOR_0 has four
// components). Its own alpha test is three.js's: map_fragment, color_fragment and alphatest_fragment
// (`diffuseColor.a < alphaTest` discards). The harness's surfaces for such a mesh are clones of the
// loaded material, so that the camera discards exactly the texels three.js discards, and three.js's
// depth pass builds its depth material from them as from the loaded one (WebGLShadowMap's
// getDepthMaterial copies `map`, `alphaMap` and `alphaTest`, nothing else).
const isMasked = (material) => material.alphaTest > 0;

// The loaded material's clone with its output replaced: `output` is GLSL that sets gl_FragColor,
// in place of the material's own colour (opaque_fragment); everything before it — the alpha test
// among it — is the material's. `pars` adds declarations ahead of main.
function withOutput(loaded, output, pars = '') {
  const material = loaded.clone();
  material.onBeforeCompile = (shader) => {
    shader.fragmentShader = shader.fragmentShader
      .replace('#include <shadowmap_pars_fragment>', `#include <shadowmap_pars_fragment>\n${pars}`)
      .replace('#include <opaque_fragment>', output);
  };
  // One program per patch: three.js keys a program by customProgramCacheKey, by default the text of
  // onBeforeCompile, which is this one closure's for both patches; the key names the output instead.
  material.customProgramCacheKey = () => `shadowref:${output}`;
  return material;
}

// The shadow pass's surface for a masked mesh: ShadowMaterial's own output, alpha = 1 − the shadow
// term (shadowmask_pars_fragment's getShadowMask, as ShadowMaterial computes it), after the loaded
// material's alpha test.
function maskedShadowMaterial(loaded, shadowSide) {
  const material = withOutput(loaded, 'gl_FragColor = vec4( 0.0, 0.0, 0.0, 1.0 - getShadowMask() );',
    '#include <shadowmask_pars_fragment>');
  material.side = THREE.DoubleSide;
  material.shadowSide = shadowSide;
  material.blending = THREE.NoBlending;
  return material;
}

// The face pass's surface for a masked mesh: the per-corner colour (coverage, facing), after the loaded
// material's alpha test (the colour attribute keeps COLOR_0's alpha, the vertex alpha).
function maskedFaceMaterial(loaded) {
  const material = withOutput(loaded, 'gl_FragColor = vec4( vColor.rgb, 1.0 );');
  material.vertexColors = true;
  material.side = THREE.DoubleSide;
  material.blending = THREE.NoBlending;
  return material;
}

// WebGPURenderer's surfaces (node materials; onBeforeCompile is WebGLRenderer's alone). The shadow
// pass: three.js's ShadowNodeMaterial, whose lighting model (ShadowMaskModel) multiplies every
// light's shadow node into alpha, as ShadowMaterial does in GLSL; opaque (not transparent, normal
// blending), so NodeMaterial sets alpha to 1 after its alpha test and the output is exactly
// 1 − the shadow term, unblended. A masked mesh's surfaces take its loaded material's map, alpha
// test, opacity and vertex colours, which NodeMaterial's own diffuse colour multiplies and
// alpha-tests as the loaded material's converted node material would (setupDiffuseColor); the
// depth pass takes `map` and `alphaTest` from the drawn material (Renderer._getShadowNodes).
function nodeShadowMaterial(shadowSide, loaded = null) {
  const material = new THREE.ShadowNodeMaterial({ color: 0x000000, opacity: 1, transparent: false, side: THREE.DoubleSide });
  if (loaded) {
    material.map = loaded.map;
    material.alphaTest = loaded.alphaTest;
    material.opacity = loaded.opacity;
    material.vertexColors = loaded.vertexColors;
  }
  material.shadowSide = shadowSide;
  return material;
}

// The face pass's surface on WebGPURenderer: the per-corner colour (coverage, facing) as the output
// itself, after the diffuse colour's alpha test for a masked mesh (the colour attribute keeps
// COLOR_0's alpha then).
function nodeFaceMaterial(loaded = null) {
  const { vec4, vertexColor } = THREE.TSL;
  const material = new THREE.MeshBasicNodeMaterial({ side: THREE.DoubleSide, vertexColors: true });
  if (loaded) {
    material.map = loaded.map;
    material.alphaTest = loaded.alphaTest;
    material.opacity = loaded.opacity;
  }
  material.outputNode = vec4(vertexColor().rgb, 1);
  return material;
}

// A mesh's triangles as the engine draws them, in world space, 9 numbers per face. A SkinnedMesh is
// posed by three.js's own skinning on the CPU (SkinnedMesh.getVertexPosition: applyBoneTransform with
// the bones' world matrices, the same linear blend the vertex shader's skinning_vertex computes);
// other meshes are the pack's world-space triangles as loaded.
function drawnPositions(m) {
  const p = m.geometry.attributes.position;
  if (!m.isSkinnedMesh) return p.array;
  const out = new Float32Array(p.count * 3), v = new THREE.Vector3();
  for (let i = 0; i < p.count; i++) {
    m.getVertexPosition(i, v).applyMatrix4(m.matrixWorld);
    out.set([v.x, v.y, v.z], 3 * i);
  }
  return out;
}

// The view and projection matrices three.js draws a light's shadow map with, read as it draws:
// WebGLShadowMap.render calls the shadow camera's updateMatrixWorld once per view it renders (a
// directional or spot light's one, through LightShadow.updateMatrices; each of a point light's six
// cube faces, +x, −x, +y, −y, +z, −z, after pointing the camera at it), and each view's matrices are
// taken right then. Column-major (Matrix4.elements), WebGL's clip space (the `gl` convention).
function recordShadowViews(shadowCamera) {
  const views = [];
  const update = shadowCamera.updateMatrixWorld;
  shadowCamera.updateMatrixWorld = function (force) {
    update.call(this, force);
    views.push({ view: [...this.matrixWorldInverse.elements], projection: [...this.projectionMatrix.elements] });
  };
  return {
    stop() {
      shadowCamera.updateMatrixWorld = update;
      return views;
    },
  };
}

async function render(url, variantName) {
  if (!renderer) return { error: 'harness.init(backend) was not called' };
  const node = onWebGPU();
  const v = VARIANTS[variantName];
  if (!v) return { error: `no three.js variant "${variantName}" (${Object.keys(VARIANTS).join(', ')})` };
  const gltf = await new GLTFLoader().loadAsync(url);
  const json = gltf.parser.json;
  const cam = packCamera(json);
  const lights = packLights(json);
  // WebGPURenderer draws a root that is not a Scene (GLTFLoader's gltf.scene is a Group) through an
  // empty Scene of its own (Renderer.render: sceneRef), and its shadow maps are drawn from that one:
  // nothing casts. WebGLRenderer draws any Object3D. The loaded scene goes into a Scene there.
  let scene = gltf.scene;
  if (node) {
    scene = new THREE.Scene();
    scene.add(gltf.scene);
  }
  const camera = gltf.cameras[0];
  camera.far = cam.far;  // the pack's finite far plane: the depth buffer's precision spent on the scene
  camera.updateProjectionMatrix();
  scene.updateMatrixWorld(true);

  const meshes = [];
  scene.traverse((o) => { if (o.isMesh) meshes.push(o); });
  if (v.bindPose) {
    for (const m of meshes) if (m.isSkinnedMesh) m.skeleton.pose();
    scene.updateMatrixWorld(true);
  }
  const bounds = new THREE.Box3();
  for (const m of meshes) bounds.expandByObject(m);
  // One vertex per face corner, with the face's normal: glTF asks a loader for flat normals when a
  // mesh has none (the pack's do not), and three.js's normalBias offsets along them.
  const loadedSide = meshes[0].material.side;
  for (const m of meshes) {
    m.geometry = m.geometry.toNonIndexed();
    m.geometry.computeVertexNormals();
    m.castShadow = true;
    m.receiveShadow = true;
    if (v.depthAlphaTest === false) {
      m.onBeforeShadow = (renderer, object, camera, shadowCamera, geometry, depthMaterial) => {
        depthMaterial.map = null;
        depthMaterial.alphaMap = null;
        depthMaterial.alphaTest = 0;
      };
    }
  }
  // The shadow pass's surface: three.js's ShadowMaterial draws alpha = 1 − its shadow term and nothing
  // else. Two-sided, because the contract's surfaces are seen from both sides; its depth pass draws
  // what three.js's would for the loaded material (or the variant's sides).
  const shadowSide = v.shadowSide ?? defaultShadowSide(v.type, loadedSide);
  let shadowMaterial, faceMaterial;
  if (node) {
    shadowMaterial = nodeShadowMaterial(shadowSide);
    faceMaterial = nodeFaceMaterial();
  } else {
    shadowMaterial = new THREE.ShadowMaterial({ color: 0x000000, opacity: 1, transparent: false, side: THREE.DoubleSide });
    shadowMaterial.blending = THREE.NoBlending;
    shadowMaterial.shadowSide = shadowSide;
    faceMaterial = new THREE.MeshBasicMaterial({ vertexColors: true, side: THREE.DoubleSide });
  }
  // Per mesh: the shadow pass's and the face pass's surfaces, and the loaded colour attribute (COLOR_0)
  // the face pass's colours replace. A masked mesh draws clones of its own material (above); every
  // other mesh ShadowMaterial and a plain vertex-colour material, which a SkinnedMesh skins like any
  // of three.js's materials (skinning_vertex), in the camera's passes and in the depth pass alike.
  const surfaces = new Map(meshes.map((m) => {
    const loaded = m.material, color = m.geometry.attributes.color;
    if (!isMasked(loaded)) return [m, { shadow: shadowMaterial, face: faceMaterial, color }];
    const side = v.shadowSide ?? defaultShadowSide(v.type, loaded.side);
    if (node) return [m, { shadow: nodeShadowMaterial(side, loaded), face: nodeFaceMaterial(loaded), color }];
    return [m, { shadow: maskedShadowMaterial(loaded, side), face: maskedFaceMaterial(loaded), color }];
  }));
  // What the candidate records of the masked and skinned meshes (settings, never judged).
  const masked = meshes.filter((m) => surfaces.get(m).shadow !== shadowMaterial).map((m) => ({
    mesh: m.name, alphaTest: m.material.alphaTest, map: m.material.map !== null, vertexAlpha: Boolean(m.geometry.attributes.color?.itemSize === 4),
    shadowSide: SIDE_NAMES[surfaces.get(m).shadow.shadowSide] }));
  const skinned = meshes.filter((m) => m.isSkinnedMesh).map((m) => ({ mesh: m.name, bones: m.skeleton.bones.length }));

  renderer.shadowMap.type = v.type;
  renderer.setSize(cam.width, cam.height, false);
  renderer.setClearColor(0x000000, 0);
  const Target = node ? THREE.RenderTarget : THREE.WebGLRenderTarget;
  const target = new Target(cam.width, cam.height, { type: THREE.UnsignedByteType, format: THREE.RGBAFormat });
  let shadowPixels = new Uint8Array(cam.width * cam.height * 4);
  let facePixels = new Uint8Array(cam.width * cam.height * 4);
  // WebGPURenderer reads a render target back asynchronously (a texture copied to a buffer), in the
  // texture's rows: top first on WebGPU, bottom first on its WebGL2 backend (readPixels).
  const readBack = async (pixels) => {
    if (!node) {
      renderer.readRenderTargetPixels(target, 0, 0, cam.width, cam.height, pixels);
      return pixels;
    }
    return new Uint8Array(await renderer.readRenderTargetPixelsAsync(target, 0, 0, cam.width, cam.height));
  };
  const topFirst = node && renderer.backend.isWebGPUBackend === true;
  // WebGPU's clip depth runs 0..w; candidate.json's projections are the gl convention's (−w..w).
  const glProjection = (p) => (renderer.coordinateSystem === THREE.WebGPUCoordinateSystem ? halfZToGl(p) : p);

  const loadedLights = [];
  scene.traverse((o) => { if (o.isLight) loadedLights[o.userData.index] = o; });
  const fits = [];
  const masks = [];
  const declared = [];  // per light: the light matrices three.js drew its map with
  for (const l of lights) {
    const { light, fit } = engineLight(scene, loadedLights[l.index], l, bounds, meshes, v);
    fits.push(fit);
    if (v.mapSize) light.shadow.mapSize.set(v.mapSize, v.mapSize);
    if (v.bias !== undefined) light.shadow.bias = v.bias;
    if (v.normalBias !== undefined) light.shadow.normalBias = v.normalBias;
    if (v.radius !== undefined) light.shadow.radius = v.radius;
    light.castShadow = true;
    let csm = null;
    if (v.csm && l.type === 'directional') {
      if (!node) throw new Error('the csm variant is WebGPURenderer\'s (CSMShadowNode)');
      // Each cascade's light stands lightMargin behind its slice of the camera's frustum, toward the
      // light, and draws with a clone of this light's shadow camera: its depth range must reach from
      // there across the scene (the default margin, 200, and far plane, 500, are a large scene's).
      const radius = bounds.getBoundingSphere(new THREE.Sphere()).radius;
      Object.assign(light.shadow.camera, { near: 0.01 * radius, far: 6 * radius });
      csm = new CSMShadowNode(light, { maxFar: camera.far, lightMargin: 2 * radius });
      light.shadow.shadowNode = csm;
      fits[fits.length - 1] = `CSMShadowNode: ${csm.cascades} cascades (${csm.mode}) up to ${camera.far.toPrecision(6)}, lightMargin ${(2 * radius).toPrecision(6)}, depth ${(0.01 * radius).toPrecision(6)}..${(6 * radius).toPrecision(6)}`;
    }
    light.shadow.camera.updateProjectionMatrix();
    for (const other of loadedLights) if (other !== light) other.visible = false;
    light.visible = true;

    for (const m of meshes) {
      const { shadow, color } = surfaces.get(m);
      if (color) m.geometry.setAttribute('color', color);
      else m.geometry.deleteAttribute('color');
      m.material = shadow;
    }
    renderer.setRenderTarget(target);
    renderer.clear();
    const views = recordShadowViews(light.shadow.camera);
    renderer.render(scene, camera);
    let drawn = views.stop();
    if (node) {
      // WebGPURenderer draws each view with renderer.render(scene, shadowCamera), which updates the
      // camera's world matrix again: the same view twice in a row, kept once (its latest projection).
      drawn = drawn.filter((d, k) => k + 1 === drawn.length || d.view.some((x, j) => x !== drawn[k + 1].view[j]))
        .map((d) => ({ view: d.view, projection: glProjection(d.projection) }));
      // Its cube faces are drawn in WebGPU's cube order (−x first): put them in candidate.json's.
      if (light.isPointLight && drawn.length === 6) drawn = cubeFacesInOrder(drawn);
    }
    // None: three.js drew no map for this light (VSM skips point lights), and has no views to declare.
    if (drawn.length !== 0 && drawn.length !== (light.isPointLight ? 6 : 1))
      throw new Error(`three.js drew ${drawn.length} shadow views for a ${light.type}, not ${light.isPointLight ? 6 : 1}`);
    let entry = drawn.length ? { light_views: 'declared', shadow_map_size: light.shadow.mapSize.x, views: drawn } : { light_views: 'own' };
    if (csm) {
      // The cascades as CSMShadowNode drew them: each cascade light's shadow camera, nearest first,
      // and where each begins and the last ends in camera depth. Its shader picks a pixel's cascade by
      // (−viewZ − near) / (shadowFar − near), shadowFar = min(maxFar, camera.far), against each
      // cascade's [from, to] (_cascades, from breaks); no fade, so no blend.
      const far = Math.min(csm.maxFar, camera.far), near = camera.near;
      entry = {
        light_views: 'declared', shadow_map_size: light.shadow.mapSize.x,
        views: csm.lights.map((c) => ({ view: [...c.shadow.camera.matrixWorldInverse.elements], projection: glProjection([...c.shadow.camera.projectionMatrix.elements]) })),
        cascade_splits: [near + csm._cascades[0].x * (far - near), ...csm._cascades.map((c) => near + c.y * (far - near))],
        cascade_blend: 0,
        cascades: csm.cascades,
      };
    }
    if (v.type === THREE.PCFShadowMap || (node && v.type !== THREE.BasicShadowMap && light.isPointLight)) {
      // r187's PCF, on both renderers (WebGLRenderer's getShadow and getPointShadow in
      // shadowmap_pars_fragment.glsl.js; WebGPURenderer's PCFShadowFilter and PointShadowFilter, which
      // its VSM maps use for point lights too): five taps on a Vogel disk turned per pixel by
      // interleaved gradient noise, each a bilinear compare. A 2D map's disk reaches 0.95 `radius`
      // texels; a cube's offsets the direction by radius / mapSize, half as many texels at a face's
      // centre (a face spans 2 in direction units), fewer toward its edges. WebGLRenderer draws no map
      // for a point light under VSM, so only WebGPURenderer's VSM point lights are here.
      const r = light.shadow.radius;
      Object.assign(entry, { filter_radius_texels: (light.isPointLight ? r / 2 : r) + 0.5, sampling: 'random' });
    }
    declared.push(entry);
    shadowPixels = await readBack(shadowPixels);

    for (const m of meshes) {
      const { face, color } = surfaces.get(m);
      const away = turnedAway(drawnPositions(m), cam.position, l.homogeneous);
      // A masked mesh's vertex alpha (COLOR_0's fourth component) stays beside the face colours: its
      // alpha test reads it.
      const alpha = face !== faceMaterial && color && color.itemSize === 4 ? color : null;
      const n = alpha ? 4 : 3;
      const colours = new Float32Array(away.length * 3 * n);
      away.forEach((a, f) => {
        for (let k = 0; k < 3; k++) colours.set(alpha ? [a ? 0 : 1, 1, 0, alpha.getW(3 * f + k)] : [a ? 0 : 1, 1, 0], n * (3 * f + k));
      });
      m.geometry.setAttribute('color', new THREE.BufferAttribute(colours, n));
      m.material = face;
    }
    light.castShadow = false;
    renderer.clear();
    renderer.render(scene, camera);
    facePixels = await readBack(facePixels);
    renderer.setRenderTarget(null);
    light.visible = false;
    // Lit when the engine's shadow term is at least ½ (alpha = 1 − term ≤ ½): one tap gives 0 or 1,
    // a filter lights a pixel when at least half its weight is lit, as the suite's own PCF does.
    masks.push(base64(combine(cam.width, cam.height, shadowPixels, facePixels, (p, i) => p[i + 3] <= 127, topFirst)));
  }
  const mapSize = v.mapSize ?? 512;
  const bias = v.bias ?? 0;
  const radius = v.radius ?? 1;  // LightShadow's default
  const candidate = withEnvironment({
    producer: 'three.js',
    version: `r${THREE.REVISION}`,
    technique: v.technique,
    convention: 'gl',
    shadow_map_size: mapSize,
    // Basic: one nearest tap. PCF: five taps on a Vogel disk of `radius` texels (the farthest at
    // 0.95 radius), each a bilinear hardware compare reaching half a texel further. VSM: the moments
    // blurred over `radius` texels each way (vsm.glsl.js), read bilinearly.
    filter_radius_texels: v.type === THREE.BasicShadowMap ? 0 : radius + 0.5,
    slope_bias_texels: 0,
    constant_bias: 0,
    // three.js's own light views, as it drew them (recordShadowViews): the judge knows the grid.
    light_views: 'declared',
    normal_offset: v.normalBias ?? 0,
    depth_bias: Math.abs(bias),
    depth_faces: SIDE_NAMES[shadowSide],
    settings: {
      renderer: { webgl2: 'WebGLRenderer', webgpu: 'WebGPURenderer', 'webgpu-webgl2': 'WebGPURenderer (forceWebGL)' }[backend],
      'renderer.shadowMap.type': TYPE_NAMES[v.type],
      'shadow.mapSize': mapSize,
      'shadow.bias': bias,
      'shadow.normalBias': v.normalBias ?? 0,
      'shadow.radius': radius,
      'material.shadowSide': SIDE_NAMES[shadowSide],
      ...(v.depthAlphaTest === false ? { 'depth pass alpha test': 'off (control)' } : {}),
      ...(v.bindPose ? { skeletons: 'bind pose (control)' } : {}),
      ...(v.csm ? { 'directional lights': 'CSMShadowNode' } : {}),
      'shadow cameras': fits,
      'spot lights': 'the point light at the spot position (the mask is occlusion everywhere)',
      'camera.far': cam.far,
      ...(masked.length ? { 'alpha-masked meshes': masked } : {}),
      ...(skinned.length ? { 'skinned meshes': skinned } : {}),
    },
    lights: declared,
  }, environment);
  for (const m of meshes) {
    m.geometry.dispose();
    const { shadow, face } = surfaces.get(m);
    if (shadow !== shadowMaterial) [shadow, face].forEach((x) => x.dispose());
  }
  [shadowMaterial, faceMaterial].forEach((x) => x.dispose());
  // WebGPURenderer keeps each light's shadow map (its ShadowNode) until the light is disposed.
  if (node) for (const l of loadedLights) l.dispose?.();
  target.dispose();
  return { width: cam.width, height: cam.height, masks, candidate };
}

window.harness = {
  init: (wanted, adapter, browser) => init(wanted, adapter, browser).catch((e) => ({ error: String(e.message || e) })),
  render: (url, variant) => render(url, variant).catch((e) => ({ error: String(e.stack || e) })),
};
