// engines/web/common.js — what the three.js and Babylon.js pages share (in the browser): the
// attached-shadow rule of engines/common/attached_shadow.hpp, the mask from the engine's shadow
// term and the harness's own face pass, and the light as the pack's homogeneous point.
//
// A mask is made of two renders of the same camera over the same geometry:
//   shadow pass: surfaces draw the engine's own shadow term for one light (1 lit .. 0 shadowed),
//                nothing else (no shading, no ambient, no cone);
//   face pass:   surfaces draw green (coverage) and red where the face is not turned away from the
//                light; the clear colour is black, so green = 0 means no surface.
// Coverage is never read from the shadow pass, so an engine's shadow cannot make a surface.

export const LIT = 255, SHADOWED = 0, NO_SURFACE = 128;

// Per face of a non-indexed triangle list (world positions, 9 numbers per face): 1 when the face,
// its normal turned toward `camera`, does not point toward `light` (x, y, z, w: a position when
// w = 1, a direction toward the light when w = 0); the tie counts as turned away, as in the reference.
export function turnedAway(positions, camera, light) {
  const faces = positions.length / 9;
  const out = new Uint8Array(faces);
  for (let f = 0; f < faces; f++) {
    const p = positions.subarray(9 * f, 9 * f + 9);
    const e1 = [p[3] - p[0], p[4] - p[1], p[5] - p[2]];
    const e2 = [p[6] - p[0], p[7] - p[1], p[8] - p[2]];
    let n = [e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2], e1[0] * e2[1] - e1[1] * e2[0]];
    const towardCamera = n[0] * (camera[0] - p[0]) + n[1] * (camera[1] - p[1]) + n[2] * (camera[2] - p[2]);
    if (towardCamera < 0) n = [-n[0], -n[1], -n[2]];
    const w = light[3];
    const toLight = [light[0] - p[0] * w, light[1] - p[1] * w, light[2] - p[2] * w];
    out[f] = n[0] * toLight[0] + n[1] * toLight[1] + n[2] * toLight[2] > 0 ? 0 : 1;
  }
  return out;
}

// The mask, row 0 at the top, from two W x H RGBA readbacks whose row 0 is the bottom (WebGL's
// readPixels) or, with `topFirst`, the top (a WebGPU texture copied to a buffer: its origin is the
// top-left corner): `lit(shadow, i)` says from the shadow pass's pixel i whether the engine lit it.
export function combine(width, height, shadowRgba, faceRgba, lit, topFirst = false) {
  const mask = new Uint8Array(width * height);
  for (let y = 0; y < height; y++)
    for (let x = 0; x < width; x++) {
      const i = ((topFirst ? y : height - 1 - y) * width + x) * 4;
      const covered = faceRgba[i + 1] >= 128;
      const facing = faceRgba[i] >= 128;
      mask[y * width + x] = !covered ? NO_SURFACE : facing && lit(shadowRgba, i) ? LIT : SHADOWED;
    }
  return mask;
}

// The lit fraction (visibility.png), row 0 at the top, from the same two readbacks: the engine's
// shadow term as it is (8 bits) where a surface faces the light, 0 where it is turned away, the
// mask's 128 where there is no surface.
export function fraction(width, height, shadowRgba, faceRgba, topFirst = false) {
  const out = new Uint8Array(width * height);
  for (let y = 0; y < height; y++)
    for (let x = 0; x < width; x++) {
      const i = ((topFirst ? y : height - 1 - y) * width + x) * 4;
      out[y * width + x] = faceRgba[i + 1] < 128 ? NO_SURFACE : faceRgba[i] >= 128 ? shadowRgba[i] : 0;
    }
  return out;
}

// Where candidate.json records the render's environment (the API, the adapter, the browser, the
// engine): its own top-level "environment" key, or, for a `shadowref conform` that does not know
// that key yet (it refuses unknown keys), inside "settings", which is recorded and never judged.
export const ENVIRONMENT_AT_TOP_LEVEL = true;

// The candidate with `environment` put where ENVIRONMENT_AT_TOP_LEVEL says.
export function withEnvironment(candidate, environment) {
  if (ENVIRONMENT_AT_TOP_LEVEL) return { ...candidate, environment };
  return { ...candidate, settings: { ...candidate.settings, environment } };
}

// A WebGPU adapter as the page reports it: vendor, architecture, device and description
// (GPUAdapterInfo), the empty ones left out.
export function adapterText(info) {
  return [info.vendor, info.architecture, info.device, info.description].filter((x) => x).join(' ');
}

// The browser as the page sees it: navigator.userAgent's Chrome/x.y.z.w (HeadlessChrome when headless).
export function browserText() {
  const m = navigator.userAgent.match(/\b(?:Headless)?Chrome\/[\d.]+/);
  return m ? m[0] : navigator.userAgent;
}

// A WebGL2 context's adapter: the unmasked vendor and renderer (WEBGL_debug_renderer_info), else
// the masked ones.
export function webglAdapterText(gl) {
  const ext = gl.getExtension('WEBGL_debug_renderer_info');
  return ext ? `${gl.getParameter(ext.UNMASKED_VENDOR_WEBGL)} ${gl.getParameter(ext.UNMASKED_RENDERER_WEBGL)}`
    : `${gl.getParameter(gl.VENDOR)} ${gl.getParameter(gl.RENDERER)}`;
}

// A projection whose clip depth runs 0..w (WebGPU's, Babylon's half-z range) as the same projection
// in OpenGL's −w..w, the `gl` convention candidate.json declares: z' = 2 z − w, i.e. the third row
// becomes twice itself less the fourth. Column-major, element [4 c + r].
export function halfZToGl(m) {
  const out = [...m];
  for (let c = 0; c < 4; c++) out[4 * c + 2] = 2 * m[4 * c + 2] - m[4 * c + 3];
  return out;
}

// A point light's six views in the order candidate.json asks (+x, −x, +y, −y, +z, −z of scene
// space), each found from the direction it looks in: a view's forward axis is −z of its view space,
// the negated third row of its rotation (column-major view matrix: elements 2, 6, 10).
export function cubeFacesInOrder(views) {
  const slot = (v) => {
    const f = [-v.view[2], -v.view[6], -v.view[10]];
    const a = f.map(Math.abs), k = a.indexOf(Math.max(...a));
    return 2 * k + (f[k] > 0 ? 0 : 1);
  };
  const out = new Array(6);
  for (const v of views) out[slot(v)] = v;
  if (out.some((v) => v === undefined)) throw new Error('the six cube views do not look along the six axes');
  return out;
}

export function base64(bytes) {
  let s = '';
  for (let i = 0; i < bytes.length; i += 0x8000) s += String.fromCharCode.apply(null, bytes.subarray(i, i + 0x8000));
  return btoa(s);
}

// The pack's camera and lights as scene.gltf has them (its JSON, as the loader read it): the
// resolution and the camera's finite far plane from the camera node's extras (the infinite
// projection's far plane is what the pack's finite one moves in, behind every object), each light's
// homogeneous point from its node matrix (glTF lights shine along the node's −z).
export function packCamera(json) {
  const node = json.nodes.find((n) => n.camera !== undefined);
  const p = node.extras.projection_finite;
  // OpenGL's finite perspective: p[2][2] = (f + n) / (n − f), p[2][3] = 2 f n / (n − f), so
  // p[2][3] / (p[2][2] + 1) = f.
  const far = p[2][3] / (p[2][2] + 1);
  const m = node.matrix;
  return { width: node.extras.resolution[0], height: node.extras.resolution[1], far, position: [m[12], m[13], m[14]] };
}

export function packLights(json) {
  const lights = [];
  json.nodes.forEach((n) => {
    const ext = n.extensions && n.extensions.KHR_lights_punctual;
    if (!ext) return;
    const def = json.extensions.KHR_lights_punctual.lights[ext.light];
    const m = n.matrix;
    const homogeneous = def.type === 'directional' ? [m[8], m[9], m[10], 0] : [m[12], m[13], m[14], 1];
    lights[ext.light] = { index: ext.light, type: def.type, kind: def.extras.shadowref_type, homogeneous,
      forward: [-m[8], -m[9], -m[10]], cone: def.spot ? def.spot.outerConeAngle : undefined,
      rect: def.extras.shadowref_type === 'rect' ? { edgeU: def.extras.edge_u, edgeV: def.extras.edge_v } : undefined };
  });
  return lights;
}
