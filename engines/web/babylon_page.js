// engines/web/babylon_page.js — the Babylon.js harness, in the page (babylon.html): loads a pack
// scene with Babylon's own glTF loader (@babylonjs/loaders) and renders one mask per light with
// Babylon's own ShadowGenerator / CascadedShadowGenerator and the variant's settings, on Babylon's
// WebGL2 Engine (`webgl2`) or its WebGPUEngine (`webgpu`, every shader WGSL: a GLSL one would make
// Babylon fetch its GLSL-to-SPIR-V compiler from a CDN); engines/README.md says what is adapted and why.
import { Engine } from '@babylonjs/core/Engines/engine.js';
import { WebGPUEngine } from '@babylonjs/core/Engines/webgpuEngine.js';
import { RenderTargetTexture } from '@babylonjs/core/Materials/Textures/renderTargetTexture.js';
import { Constants } from '@babylonjs/core/Engines/constants.js';
import { ShaderLanguage } from '@babylonjs/core/Materials/shaderLanguage.js';
import { Scene } from '@babylonjs/core/scene.js';
import { Color4 } from '@babylonjs/core/Maths/math.color.js';
import { Vector3 } from '@babylonjs/core/Maths/math.vector.js';
import { AppendSceneAsync } from '@babylonjs/core/Loading/sceneLoader.js';
import { StandardMaterial } from '@babylonjs/core/Materials/standardMaterial.js';
import { ShaderMaterial } from '@babylonjs/core/Materials/shaderMaterial.js';
import { Effect } from '@babylonjs/core/Materials/effect.js';
import { MaterialPluginBase } from '@babylonjs/core/Materials/materialPluginBase.js';
import { VertexBuffer } from '@babylonjs/core/Buffers/buffer.js';
import { PointLight } from '@babylonjs/core/Lights/pointLight.js';
import { SpotLight } from '@babylonjs/core/Lights/spotLight.js';
import { ShadowGenerator } from '@babylonjs/core/Lights/Shadows/shadowGenerator.js';
import { CascadedShadowGenerator } from '@babylonjs/core/Lights/Shadows/cascadedShadowGenerator.js';
import '@babylonjs/core/Lights/Shadows/shadowGeneratorSceneComponent.js';
import '@babylonjs/core/Loading/loadingScreen.js';
import '@babylonjs/loaders/glTF/2.0/glTFLoader.js';
import '@babylonjs/loaders/glTF/2.0/Extensions/KHR_lights_punctual.js';
import '@babylonjs/loaders/glTF/glTFFileLoader.js';
import { turnedAway, combine, fraction, base64, packCamera, packLights, withEnvironment, adapterText, webglAdapterText,
  browserText, halfZToGl } from './common.js';

// Babylon's defaults (src/Lights/Shadows/shadowGenerator.ts, ShadowGenerator's constructor and
// _initializeShadowGenerator): bias 0.00005, normalBias 0, filter none, darkness 0; the map size
// is the constructor's argument (1024 in the documentation's examples). "Recommended": the
// documentation's shadows page advises PCF on WebGL2 (usePercentageCloserFiltering, quality high),
// and cascaded shadow maps for directional lights (CascadedShadowGenerator, 4 cascades).
const VARIANTS = {
  none: { filter: 'none', technique: 'shadowmap' },
  pcf: { filter: 'pcf', technique: 'shadowmap-pcf' },
  csm: { filter: 'pcf', technique: 'csm-pcf', cascaded: true },
  // Controls of `none`, one setting each. none-back-faces: forceBackFacesOnly, Babylon's switch to
  // draw only back faces in the depth pass (its documented cure for acne). none-bias-0.005: the
  // bias 100 times Babylon's default.
  'none-back-faces': { filter: 'none', technique: 'shadowmap', forceBackFacesOnly: true },
  'none-bias-0.005': { filter: 'none', technique: 'shadowmap', bias: 0.005 },
  // none-bias-0.005-no-alpha-test: none-bias-0.005 with the alpha test taken out of Babylon's depth
  // pass alone: useOpacityTextureForTransparentShadow makes the generator take the material's
  // opacityTexture (none on a glTF material) in place of its alpha-test texture, so no ALPHATEXTURE
  // reaches the shadowMap shader; the camera's pass keeps its own alpha test.
  'none-bias-0.005-no-alpha-test': { filter: 'none', technique: 'shadowmap', bias: 0.005, depthAlphaTest: false },
  // Contact-hardening shadows (useContactHardeningShadow: Babylon's PCSS), judged as pcss where
  // Babylon can draw them for the scene's light: its PCSS needs a single-view light (on a cube it
  // falls back to Poisson PCF: ShadowGenerator's filter setter), so a rect light is the spot light at
  // its centre, aimed at the scene's box and wide enough for it; the runs take the rect-light scenes
  // whose box one such cone covers (light_bleeding 130 degrees, soft_penumbra 166; cornell_box and
  // soft_cube_seam would need more than 170, with their light at the ceiling or beside the wall).
  // pcss: Babylon's light size (contactHardeningLightSizeUVRatio 0.1) and bias; pcss-light-size, its
  // control: the light size set to the rect's (lightSizeFromRect below).
  pcss: { filter: 'pcss', technique: 'pcss', rectAsSpot: true },
  'pcss-light-size': { filter: 'pcss', technique: 'pcss', rectAsSpot: true, lightSizeFromRect: true },
};

// A rect light as Babylon's spot light at its centre: aimed at the centre of the meshes' box, its
// cone (the shadow frustum's angle) reaching every corner of the box with 5 degrees to spare, at
// most 170 degrees; the shadow depth range from a hundredth of the distance to the box's centre to
// its farthest corner.
function spotForRect(scene, meshes, l) {
  const { min, max } = scene.getWorldExtends((m) => meshes.includes(m));
  const at = new Vector3(...l.homogeneous.slice(0, 3));
  const centre = min.add(max).scale(0.5);
  const axis = centre.subtract(at).normalize();
  let half = 0, far = 0;
  for (let k = 0; k < 8; k++) {
    const corner = new Vector3(k & 1 ? max.x : min.x, k & 2 ? max.y : min.y, k & 4 ? max.z : min.z);
    const d = corner.subtract(at);
    far = Math.max(far, d.length());
    if (d.length() > 0) half = Math.max(half, Math.acos(Math.min(1, Vector3.Dot(d.normalize(), axis))));
  }
  const angle = Math.min(2 * half + (10 * Math.PI) / 180, (170 * Math.PI) / 180);
  const light = new SpotLight('rect-as-spot', at, axis, angle, 1, scene);
  light.shadowMinZ = 0.01 * centre.subtract(at).length();
  light.shadowMaxZ = 1.01 * far;
  return { light, angle, distance: centre.subtract(at).length() };
}

// The control's light size: Babylon's PCSS searches a disk of `ratio` (in map uv) and filters a
// radius of ratio x (receiver - blocker depth, over the depth range); a light of half-width a
// casts, seen in the map of a perspective view of angle phi, a penumbra of radius
// a (d_r - d_b) / (2 tan(phi / 2) d_b d_r). The two agree, for the depth range's span, where
// d_b d_r = D^2, D the distance to the scene's centre: ratio = a (maxZ - minZ) / (2 tan(phi / 2) D^2).
function lightSizeFromRect(l, spot) {
  const u = l.rect.edgeU, v = l.rect.edgeV;
  const cross = [u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]];
  const half = Math.sqrt(Math.hypot(...cross)) / 2;  // half the side of the rect's equal-area square
  const span = spot.light.shadowMaxZ - spot.light.shadowMinZ;
  return (half * span) / (2 * Math.tan(spot.angle / 2) * spot.distance * spot.distance);
}
const MAP_SIZE = 1024;

// The view and projection matrices Babylon draws a generator's map with, read as it draws:
// ShadowGenerator.getTransformMatrix computes them for the face the map is rendering
// (_currentFaceIndex: a point light's six cube faces, one view otherwise) into _viewMatrix and
// _projectionMatrix, always left-handed (LookAtLH, PerspectiveFovLH / OrthoOffCenterLH) whatever the
// scene's handedness, with WebGL's clip depth −1..1. Babylon's matrices are row-vector, so a
// Matrix's `m` array, row-major, is the column-vector matrix in column-major order: what
// candidate.json asks for. A cube's faces are declared in the order +x, −x, +y, −y, +z, −z, found
// from each face's direction (PointLight.getShadowDirection: Babylon's face 2 looks down −y).
function recordShadowViews(generator, light) {
  const faces = new Map();
  const get = generator.getTransformMatrix;
  generator.getTransformMatrix = function () {
    const transform = get.call(this);
    faces.set(this._currentFaceIndex, { view: [...this._viewMatrix.m], projection: [...this._projectionMatrix.m] });
    return transform;
  };
  return {
    stop() {
      generator.getTransformMatrix = get;
      if (!light.needCube()) return faces.has(0) ? [faces.get(0)] : [];
      const slots = [];
      for (const [face, matrices] of faces) {
        const d = light.getShadowDirection(face);
        const axis = Math.abs(d.x) >= Math.abs(d.y) && Math.abs(d.x) >= Math.abs(d.z) ? 0 : Math.abs(d.y) >= Math.abs(d.z) ? 1 : 2;
        slots[2 * axis + ([d.x, d.y, d.z][axis] >= 0 ? 0 : 1)] = matrices;
      }
      return slots.filter((v) => v).length === 6 ? slots : [];
    },
  };
}

// A CascadedShadowGenerator's cascades as it drew them: each cascade's view and projection (kept
// per cascade, left-handed and WebGL-depth as a single view's), and the camera depths where each
// cascade begins and the last ends. Babylon picks a pixel's cascade by its view-space depth against
// _viewSpaceFrustumsZ (each cascade's far end: near + breakDistance × the camera's range,
// _splitFrustum) and blends each cascade into the next over the far cascadeBlendPercentage of its
// depth range (Shaders/ShadersInclude/lightFragment.fx): candidate.json's cascade_splits and
// cascade_blend.
function cascadeViews(generator) {
  const camera = generator._getCamera();
  const near = camera.minZ, range = (camera.maxZ || generator.shadowMaxZ) - near;
  const views = [], splits = [];
  for (let i = 0; i < generator.numCascades; i++) {
    views.push({ view: [...generator.getCascadeViewMatrix(i).m], projection: [...generator.getCascadeProjectionMatrix(i).m] });
    if (i === 0) splits.push(near + generator._cascades[0].prevBreakDistance * range);
    splits.push(near + generator._cascades[i].breakDistance * range);
  }
  return { views, splits };
}

// The shadow pass's surface: Babylon's StandardMaterial with every light term computed as usual,
// whose final colour is replaced by the shadow term the light loop left in `shadow`
// (Shaders/ShadersInclude/lightFragment.fx: one light enabled, so it is that light's).
class ShadowTerm extends MaterialPluginBase {
  constructor(material) {
    super(material, 'ShadowTerm', 1000, {}, true, true);
  }
  getClassName() { return 'ShadowTerm'; }
  isCompatible() { return true; }
  getCustomCode(shaderType, language) {
    const vec4 = language === ShaderLanguage.WGSL ? 'vec4f' : 'vec4';
    return shaderType === 'fragment' ? { CUSTOM_FRAGMENT_BEFORE_FRAGCOLOR: `color = ${vec4}(shadow, shadow, shadow, 1.0);` } : null;
  }
}

// The same output for a material the glTF loader made (PBRMaterial, whose final colour is
// `finalColor`): the harness's surface for an alpha-masked mesh is a clone of its loaded material,
// so that Babylon's own alpha test runs before the output is replaced (pbrBlockAlbedoOpacity: alpha =
// the albedo texture's alpha x COLOR_0's (VERTEXALPHA) x the factor's, discarded below
// ALPHATESTVALUE, the glTF alphaCutoff), and Babylon's depth pass takes its alpha test from it as from
// the loaded material (ShadowGenerator.isReady: needAlphaTestingForMesh, getAlphaTestTexture).
class PbrShadowTerm extends MaterialPluginBase {
  constructor(material) {
    super(material, 'PbrShadowTerm', 1000, {}, true, true);
  }
  getClassName() { return 'PbrShadowTerm'; }
  isCompatible() { return true; }
  getCustomCode(shaderType, language) {
    const vec4 = language === ShaderLanguage.WGSL ? 'vec4f' : 'vec4';
    return shaderType === 'fragment' ? { CUSTOM_FRAGMENT_BEFORE_FRAGCOLOR: `finalColor = ${vec4}(shadow, shadow, shadow, 1.0);` } : null;
  }
}

// The face pass drawn by one of Babylon's own materials (for the meshes whose vertices Babylon
// transforms itself: skinned ones, by its bones, and masked ones, whose alpha test must run): the
// vertex colour the face pass sets, in place of the final colour (`color` in StandardMaterial,
// `finalColor` in PBRMaterial).
class FaceColour extends MaterialPluginBase {
  constructor(material, output) {
    super(material, 'FaceColour', 1000, {}, true, true);
    this.output = output;
  }
  getClassName() { return 'FaceColour'; }
  isCompatible() { return true; }
  getCustomCode(shaderType, language) {
    const code = language === ShaderLanguage.WGSL ? `${this.output} = vec4f(fragmentInputs.vColor.rgb, 1.0);` : `${this.output} = vec4(vColor.rgb, 1.0);`;
    return shaderType === 'fragment' ? { CUSTOM_FRAGMENT_BEFORE_FRAGCOLOR: code } : null;
  }
}

// The face pass: each vertex's colour, nothing else.
Effect.ShadersStore.shadowrefFacesVertexShader = `precision highp float;
attribute vec3 position; attribute vec4 color; uniform mat4 worldViewProjection; varying vec4 vColor;
void main() { vColor = color; gl_Position = worldViewProjection * vec4(position, 1.0); }`;
Effect.ShadersStore.shadowrefFacesFragmentShader = `precision highp float;
varying vec4 vColor; void main() { gl_FragColor = vec4(vColor.rgb, 1.0); }`;

const canvas = document.createElement('canvas');
document.body.appendChild(canvas);
// The page's one engine and the environment it runs in, made by init(backend) before any scene.
let engine = null, environment = null;

// Makes the engine the backend asks for and refuses any other: a mask is never recorded as one
// backend's when another drew it. `adapterWanted`, when given, must occur in the adapter's description.
async function init(wanted, adapterWanted, browser) {
  if (wanted === 'webgl2') {
    engine = new Engine(canvas, false, { preserveDrawingBuffer: true, stencil: true, antialias: false, adaptToDeviceRatio: false });
    if (engine.webGLVersion !== 2) return { error: `asked for Babylon.js on WebGL2, but its Engine runs WebGL ${engine.webGLVersion}: no mask written` };
    environment = { api: 'webgl2', adapter: webglAdapterText(engine._gl) };
  } else if (wanted === 'webgpu') {
    if (!navigator.gpu) return { error: 'asked for Babylon.js WebGPUEngine, but the page has no WebGPU (navigator.gpu is missing): no mask written' };
    engine = new WebGPUEngine(canvas, { stencil: true, antialias: false, adaptToDeviceRatio: false });
    try {
      await engine.initAsync();
    } catch (e) {
      return { error: `asked for Babylon.js WebGPUEngine, but it found no WebGPU adapter (${String(e.message || e).split('\n')[0]}): no mask written` };
    }
    if (!engine.isWebGPU || !engine._adapterInfo)
      return { error: 'asked for Babylon.js WebGPUEngine, but it does not run on a WebGPU adapter: no mask written' };
    environment = { api: 'webgpu', adapter: adapterText(engine._adapterInfo) };
  } else {
    return { error: `no Babylon.js backend "${wanted}" (webgl2, webgpu)` };
  }
  if (adapterWanted && !environment.adapter.toLowerCase().includes(adapterWanted.toLowerCase()))
    return { error: `asked for the adapter "${adapterWanted}", but Babylon.js runs on "${environment.adapter}": no mask written` };
  Object.assign(environment, { browser: browser || browserText(), engine: `Babylon.js ${Engine.Version}` });
  return { environment };
}

// One frame's colour as RGBA bytes, bottom row first. On WebGL2 the canvas (its drawing buffer
// preserved); on WebGPU the camera draws into a render target instead (a WebGPU canvas reads back
// blank in headless Chromium), which Babylon reads back in WebGL's row order too.
async function renderFrame(scene) {
  await scene.whenReadyAsync();
  scene.render();
  const target = scene.activeCamera.outputRenderTarget;
  if (target) return await target.readPixels();
  return await engine.readPixels(0, 0, engine.getRenderWidth(), engine.getRenderHeight());
}

async function render(url, variantName) {
  if (!engine) return { error: 'harness.init(backend) was not called' };
  const webgpu = engine.isWebGPU;
  const v = VARIANTS[variantName];
  if (!v) return { error: `no Babylon variant "${variantName}" (${Object.keys(VARIANTS).join(', ')})` };
  const json = await (await fetch(url)).json();
  const cam = packCamera(json);
  const lights = packLights(json);
  canvas.width = cam.width;
  canvas.height = cam.height;
  engine.setSize(cam.width, cam.height);
  engine.setHardwareScalingLevel(1);

  const scene = new Scene(engine);
  // The pack is right-handed like glTF: Babylon then loads it as it is (no __root__ mirror).
  scene.useRightHandedSystem = true;
  scene.clearColor = new Color4(0, 0, 0, 0);
  scene.ambientColor.set(0, 0, 0);
  await AppendSceneAsync(url, scene);
  const camera = scene.cameras.find((c) => c.name === 'camera');
  camera.maxZ = cam.far;  // the pack's finite far plane: the depth buffer's precision spent on the scene
  scene.activeCamera = camera;
  if (webgpu) {
    camera.outputRenderTarget = new RenderTargetTexture('shadowref-frame', { width: cam.width, height: cam.height }, scene,
      { generateMipMaps: false, type: Constants.TEXTURETYPE_UNSIGNED_BYTE, samplingMode: Constants.TEXTURE_NEAREST_SAMPLINGMODE,
        generateDepthBuffer: true, generateStencilBuffer: true });
  }
  // WebGPU's clip depth runs 0..w (Babylon's isNDCHalfZRange): candidate.json's projections are −w..w.
  const glProjection = (views) => (engine.isNDCHalfZRange ? views.map((x) => ({ view: x.view, projection: halfZToGl(x.projection) })) : views);

  const meshes = scene.meshes.filter((m) => m.getTotalVertices() > 0);
  // One vertex per face corner with the face's normal (glTF asks for flat normals when a mesh has
  // none), and the face pass's colours per corner.
  for (const m of meshes) m.convertToFlatShadedMesh();
  const shadowMaterial = new StandardMaterial('shadow-term', scene);
  new ShadowTerm(shadowMaterial);
  const faceMaterial = new ShaderMaterial('faces', scene, { vertex: 'shadowrefFaces', fragment: 'shadowrefFaces' },
    { attributes: ['position', 'color'], uniforms: ['worldViewProjection'] });
  faceMaterial.backFaceCulling = false;
  // The loaded glTF materials cull back faces (doubleSided false) and Babylon's depth pass draws what
  // the caster's material draws: the shadow pass keeps that culling.
  const loadedCulling = meshes[0].material ? meshes[0].material.backFaceCulling : true;
  shadowMaterial.backFaceCulling = loadedCulling;
  // Per mesh, the surfaces of the two passes and the loaded vertex colours (COLOR_0) the face pass's
  // colours stand in for. An alpha-masked mesh (its loaded material needs alpha testing: glTF's MASK)
  // draws clones of its loaded material, its culling as loaded (a doubleSided card's both faces, in
  // the depth pass too). A skinned mesh draws the shadow-term StandardMaterial, which Babylon skins
  // in the camera's pass and its depth pass alike (bonesVertex), and its face pass a StandardMaterial
  // too, so that both passes place its vertices with the same skinning.
  const surfaces = new Map(meshes.map((m) => {
    const colours = m.isVerticesDataPresent(VertexBuffer.ColorKind) ? m.getVerticesData(VertexBuffer.ColorKind) : null;
    if (m.material && m.material.needAlphaTestingForMesh(m)) {
      const shadow = m.material.clone(`${m.material.name}-shadow-term`);
      new PbrShadowTerm(shadow);
      const face = m.material.clone(`${m.material.name}-faces`);
      new FaceColour(face, 'finalColor');
      face.backFaceCulling = false;
      return [m, { shadow, face, colours, masked: true }];
    }
    // On WebGPU every mesh's face pass is a StandardMaterial (WGSL), the face shader being GLSL.
    if (m.skeleton || webgpu) {
      const face = new StandardMaterial(`${m.name}-faces`, scene);
      new FaceColour(face, 'color');
      face.backFaceCulling = false;
      return [m, { shadow: shadowMaterial, face, colours }];
    }
    return [m, { shadow: shadowMaterial, face: faceMaterial, colours }];
  }));
  const maskedMeshes = meshes.filter((m) => surfaces.get(m).masked).map((m) => ({ mesh: m.name,
    alphaCutOff: m.material.alphaCutOff, alphaTestTexture: Boolean(m.material.getAlphaTestTexture()), hasVertexAlpha: m.hasVertexAlpha,
    backFaceCulling: m.material.backFaceCulling }));
  const skinnedMeshes = meshes.filter((m) => m.skeleton).map((m) => ({ mesh: m.name, bones: m.skeleton.bones.length }));

  const loadedLights = lights.map((l) => scene.lights.find((b) => b.name === `light_${l.index}`));
  const masks = [];
  const visibility = [];
  const declared = [];
  const lightViews = [];  // per light: the light matrices Babylon drew its map with (recordShadowViews)
  for (const l of lights) {
    let light = loadedLights[l.index];
    // A spot light is the point light at its position, as in the other harnesses: the mask is
    // occlusion everywhere, and Babylon's spot shadow covers only its cone.
    if (l.type === 'spot') light = new PointLight('spot-as-point', new Vector3(...l.homogeneous.slice(0, 3)), scene);
    const spot = v.rectAsSpot && l.rect ? spotForRect(scene, meshes, l) : null;
    if (spot) light = spot.light;
    // A directional light's shadow map is drawn from its `position` (Babylon's documentation:
    // "the position of the light is used to compute the shadow map"), which glTF leaves at the
    // origin, inside the scene: the light is set outside the scene's bounding sphere, looking at its
    // centre along the glTF direction, with the depth range over the sphere, as three.js's harness fits
    // its box. Point lights keep Babylon's depth range (the camera's minZ..maxZ).
    let fit = spot ? `shadowMinZ..shadowMaxZ ${spot.light.shadowMinZ.toPrecision(6)}..${spot.light.shadowMaxZ.toPrecision(6)}`
                   : 'Babylon defaults (the camera minZ..maxZ)';
    if (l.type === 'directional') {
      const { min, max } = scene.getWorldExtends((m) => meshes.includes(m));
      const centre = min.add(max).scale(0.5), radius = max.subtract(min).length() / 2;
      const toward = new Vector3(...l.homogeneous.slice(0, 3)).normalize();
      light.parent = null;
      light.direction = toward.scale(-1);
      light.position = centre.add(toward.scale(2 * radius));
      light.shadowMinZ = radius;
      light.shadowMaxZ = 3 * radius;
      fit = `position 2 radii from the bounding sphere's centre, shadowMinZ..shadowMaxZ ${radius.toPrecision(6)}..${(3 * radius).toPrecision(6)}`;
    }
    for (const other of scene.lights) other.setEnabled(other === light);
    const cascaded = v.cascaded && l.type === 'directional';
    const generator = cascaded ? new CascadedShadowGenerator(MAP_SIZE, light) : new ShadowGenerator(MAP_SIZE, light);
    if (v.filter === 'pcf') {
      generator.usePercentageCloserFiltering = true;
      generator.filteringQuality = ShadowGenerator.QUALITY_HIGH;
    }
    if (v.filter === 'pcss') {
      generator.useContactHardeningShadow = true;
      generator.filteringQuality = ShadowGenerator.QUALITY_HIGH;
      if (v.lightSizeFromRect && spot) generator.contactHardeningLightSizeUVRatio = lightSizeFromRect(l, spot);
    }
    if (v.bias !== undefined) generator.bias = v.bias;
    if (v.forceBackFacesOnly) generator.forceBackFacesOnly = true;
    if (v.depthAlphaTest === false) generator.useOpacityTextureForTransparentShadow = true;
    for (const m of meshes) {
      generator.addShadowCaster(m, false);
      m.receiveShadows = true;
      m.material = surfaces.get(m).shadow;
    }
    const views = cascaded ? null : recordShadowViews(generator, light);
    const shadowPixels = new Uint8Array(await renderFrame(scene));
    const cascades = cascaded ? cascadeViews(generator) : null;
    const drawn = glProjection(cascaded ? cascades.views : views.stop());
    const expected = cascaded ? generator.numCascades : light.needCube() ? 6 : 1;
    if (drawn.length !== expected)
      throw new Error(`Babylon drew ${drawn.length} shadow views for a ${light.getClassName()}, not ${expected}`);
    lightViews.push({ light_views: 'declared', shadow_map_size: MAP_SIZE, views: drawn,
      ...(cascaded ? { cascade_splits: cascades.splits, cascade_blend: generator.cascadeBlendPercentage } : {}) });

    for (const m of meshes) {
      const { face, colours: loaded } = surfaces.get(m);
      // The triangles as Babylon draws them: a skinned mesh posed by Babylon's own skinning on the
      // CPU (getPositionData with the skeleton: the same bone matrices and weights as bonesVertex),
      // then the mesh's world matrix.
      if (m.skeleton) m.skeleton.prepare(true);
      const positions = m.skeleton ? Float32Array.from(m.getPositionData(true, true)) : new Float32Array(m.getVerticesData(VertexBuffer.PositionKind));
      const world = m.getWorldMatrix();
      for (let i = 0; i < positions.length; i += 3) {
        const p = Vector3.TransformCoordinates(new Vector3(positions[i], positions[i + 1], positions[i + 2]), world);
        positions.set([p.x, p.y, p.z], i);
      }
      const away = turnedAway(positions, cam.position, l.homogeneous);
      const colours = new Float32Array(away.length * 12);
      // A masked mesh's vertex alpha (COLOR_0's) stays the alpha its own alpha test reads.
      const alpha = (f, k) => (loaded && m.hasVertexAlpha ? loaded[4 * (3 * f + k) + 3] : 1);
      away.forEach((a, f) => { for (let k = 0; k < 3; k++) colours.set([a ? 0 : 1, 1, 0, alpha(f, k)], 12 * f + 4 * k); });
      m.setVerticesData(VertexBuffer.ColorKind, colours, false, 4);
      m.material = face;
    }
    const facePixels = new Uint8Array(await renderFrame(scene));
    for (const m of meshes) {
      const { colours } = surfaces.get(m);
      if (colours) m.setVerticesData(VertexBuffer.ColorKind, colours, false, 4);
      else m.removeVerticesData(VertexBuffer.ColorKind);
    }
    const filterName = { [ShadowGenerator.FILTER_NONE]: 'none', [ShadowGenerator.FILTER_PCF]: 'pcf',
      [ShadowGenerator.FILTER_POISSONSAMPLING]: 'poisson', [ShadowGenerator.FILTER_PCSS]: 'pcss' }[generator.filter] ??
      String(generator.filter);
    declared.push({ light: l.index, fit, generator: cascaded ? 'CascadedShadowGenerator' : 'ShadowGenerator', filter: filterName,
      bias: generator.bias, normalBias: generator.normalBias, forceBackFacesOnly: generator.forceBackFacesOnly,
      ...(v.depthAlphaTest === false ? { useOpacityTextureForTransparentShadow: true } : {}),
      ...(cascaded ? { numCascades: generator.numCascades, lambda: generator.lambda } : {}),
      ...(generator.filter === ShadowGenerator.FILTER_PCSS ? { contactHardeningLightSizeUVRatio: generator.contactHardeningLightSizeUVRatio } : {}),
      ...(spot ? { light: `SpotLight at the rect's centre, angle ${spot.angle.toFixed(4)} rad` } : {}) });
    generator.dispose();
    if (light !== loadedLights[l.index]) light.dispose();
    // Lit when the engine's shadow term is at least ½: one tap gives 0 or 1, a filter lights a pixel
    // when at least half its weight is lit, as the suite's own PCF does.
    masks.push(base64(combine(cam.width, cam.height, shadowPixels, facePixels, (p, i) => p[i] >= 128)));
    if (v.filter === 'pcss' && l.rect) visibility.push({ light: l.index, png: base64(fraction(cam.width, cam.height, shadowPixels, facePixels)) });
  }
  const first = declared[0] ?? { filter: v.filter, bias: 0.00005, normalBias: 0 };
  // Babylon's PCF (QUALITY_HIGH) is its 6x6-tap kernel over bilinear compares (computeShadowWithPCF5,
  // Shaders/ShadersInclude/shadowsFragmentFunctions.fx): reach 2.5 texels + the bilinear's half; on a
  // point light's cube Babylon replaces PCF with Poisson sampling (computeShadowWithPoissonSamplingCube:
  // four nearest taps about one texel diagonal away, 1.5 with the texel's own half).
  const reach = { none: 0, pcf: 3, poisson: 1.5, pcss: 0 };
  const candidate = withEnvironment({
    producer: 'Babylon.js',
    version: Engine.Version,
    technique: v.technique,
    convention: 'gl',
    shadow_map_size: MAP_SIZE,
    filter_radius_texels: Math.max(...declared.map((d) => reach[d.filter] ?? 0), 0),
    // PCSS (computeShadowWithPCSS64): 64 Poisson taps turned per pixel by noise (getRand).
    ...(v.filter === 'pcss' ? { light_taps: 8, sampling: 'random' } : {}),
    slope_bias_texels: 0,
    constant_bias: 0,
    // Babylon's own light views, as it drew them (recordShadowViews, cascadeViews): the judge knows the grid.
    light_views: 'declared',
    normal_offset: first.normalBias,
    depth_bias: Math.abs(first.bias),
    depth_faces: v.forceBackFacesOnly ? 'back' : loadedCulling ? 'front' : 'both',
    ...(v.cascaded ? { cascades: 4 } : {}),
    settings: {
      engine: webgpu ? 'WebGPUEngine' : 'Engine',
      'scene.useRightHandedSystem': true,
      'material.backFaceCulling': loadedCulling,
      generators: declared,
      'spot lights': 'the point light at the spot position (the mask is occlusion everywhere)',
      ...(v.rectAsSpot ? { 'rect lights': "Babylon's SpotLight at the rect's centre (its PCSS needs one view)" } : {}),
      'camera.maxZ': cam.far,
      ...(maskedMeshes.length ? { 'alpha-masked meshes': maskedMeshes } : {}),
      ...(skinnedMeshes.length ? { 'skinned meshes': skinnedMeshes } : {}),
    },
    lights: lightViews,
  }, environment);
  scene.dispose();
  return { width: cam.width, height: cam.height, masks, visibility, candidate };
}

window.harness = {
  init: (wanted, adapter, browser) => init(wanted, adapter, browser).catch((e) => ({ error: String(e.message || e) })),
  render: (url, variant) => render(url, variant).catch((e) => ({ error: String(e.stack || e) })),
};
