// engines/web/render.mjs — renders the exported pack with a web engine (three.js or Babylon.js) in
// headless Chromium, WebGL2 or WebGPU on SwiftShader, and writes a candidate folder for
// `shadowref conform --candidate-dir`, as engines/README.md describes for every harness:
//
//   node render.mjs --engine three|babylon --pack DIR --out DIR --variant V [--scenes a,b]
//                   [--backend webgl2|webgpu|webgpu-webgl2] [--adapter TEXT] [--no-webgpu-flags]
//   node render.mjs --engine three|babylon --pack DIR --batch FILE [--backend ...] [...]
//
// --batch: several variants of one engine and backend in one browser and one page, each into its own
// folder: FILE is a JSON list of {"variant": V, "out": DIR, "scenes": [names] (optional: all)}. The
// page keeps nothing of one render for the next (each loads its scene afresh and sets every
// setting its variant names), so each folder is what a run of its variant alone writes; what is
// shared is Chromium's start and the engine's loading (about 5 s for Babylon.js, 2 s for three.js).
//
// --backend: webgl2 (the default: three.js's WebGLRenderer, Babylon's Engine), webgpu (three.js's
// WebGPURenderer, Babylon's WebGPUEngine, on WebGPU), webgpu-webgl2 (three.js's WebGPURenderer on
// its own WebGL2 backend). The page refuses to render on any other backend than the one asked for,
// or on an adapter whose description lacks --adapter's text: one line, exit 1, no mask.
// --no-webgpu-flags starts Chromium without the flags that give it WebGPU (the refusal's test).
//
// It reads the pack alone: manifest.json for the scene names, <scene>/scene.gltf (through the
// engine's own glTF loader, in the page). The pages and the engines' modules are served from the
// local disk by a small static server on 127.0.0.1; the browser is told to fetch nothing else.
import http from 'node:http';
import fs from 'node:fs';
import path from 'node:path';
import zlib from 'node:zlib';
import { fileURLToPath } from 'node:url';
import puppeteer from 'puppeteer-core';

const HERE = path.dirname(fileURLToPath(import.meta.url));

const USAGE = 'usage: render.mjs --engine three|babylon --pack DIR (--out DIR --variant V [--scenes a,b] | --batch FILE)' +
  ' [--chromium EXE] [--backend webgl2|webgpu|webgpu-webgl2] [--adapter TEXT] [--no-webgpu-flags]';

function parseArgs(argv) {
  const a = { scenes: '', backend: 'webgl2', adapter: '', webgpuFlags: true };
  for (let i = 0; i < argv.length; i += 2) {
    const key = argv[i].replace(/^--/, '');
    if (key === 'no-webgpu-flags') {
      a.webgpuFlags = false;
      i -= 1;
      continue;
    }
    if (!['engine', 'pack', 'out', 'variant', 'scenes', 'chromium', 'backend', 'adapter', 'batch'].includes(key) || i + 1 >= argv.length)
      throw new Error(`${USAGE} (at ${argv[i]})`);
    a[key] = argv[i + 1];
  }
  if (!['webgl2', 'webgpu', 'webgpu-webgl2'].includes(a.backend)) throw new Error(`--backend ${a.backend}: ${USAGE}`);
  for (const k of ['engine', 'pack']) if (!a[k]) throw new Error(`--${k} is required`);
  if (a.batch) {
    if (a.out || a.variant || a.scenes) throw new Error(`--batch gives each variant its folder and scenes: ${USAGE}`);
    const jobs = JSON.parse(fs.readFileSync(a.batch, 'utf8'));
    if (!Array.isArray(jobs) || !jobs.length || jobs.some((j) => typeof j.variant !== 'string' || typeof j.out !== 'string' ||
        (j.scenes !== undefined && !Array.isArray(j.scenes))))
      throw new Error(`${a.batch}: a batch is a non-empty list of {"variant": V, "out": DIR, "scenes": [names]}`);
    a.jobs = jobs;
  } else {
    for (const k of ['out', 'variant']) if (!a[k]) throw new Error(`--${k} is required`);
    a.jobs = [{ variant: a.variant, out: a.out, scenes: a.scenes ? a.scenes.split(',') : undefined }];
  }
  return a;
}

// PNG: 8-bit greyscale, no interlace, every row filter 0 (none). The CRC is PNG's (ISO 3309).
const CRC_TABLE = Array.from({ length: 256 }, (_, n) => {
  let c = n;
  for (let k = 0; k < 8; k++) c = c & 1 ? 0xedb88320 ^ (c >>> 1) : c >>> 1;
  return c >>> 0;
});
function crc32(buf) {
  let c = 0xffffffff;
  for (const b of buf) c = CRC_TABLE[(c ^ b) & 0xff] ^ (c >>> 8);
  return (c ^ 0xffffffff) >>> 0;
}
function chunk(type, data) {
  const len = Buffer.alloc(4);
  len.writeUInt32BE(data.length);
  const body = Buffer.concat([Buffer.from(type, 'ascii'), data]);
  const crc = Buffer.alloc(4);
  crc.writeUInt32BE(crc32(body));
  return Buffer.concat([len, body, crc]);
}
export function greyPng(width, height, pixels) {
  const ihdr = Buffer.alloc(13);
  ihdr.writeUInt32BE(width, 0);
  ihdr.writeUInt32BE(height, 4);
  ihdr[8] = 8;  // bit depth
  ihdr[9] = 0;  // greyscale
  const raw = Buffer.alloc((width + 1) * height);
  for (let y = 0; y < height; y++) pixels.copy(raw, y * (width + 1) + 1, y * width, (y + 1) * width);
  return Buffer.concat([Buffer.from([0x89, 0x50, 0x4e, 0x47, 0x0d, 0x0a, 0x1a, 0x0a]), chunk('IHDR', ihdr),
    chunk('IDAT', zlib.deflateSync(raw)), chunk('IEND', Buffer.alloc(0))]);
}

const TYPES = { '.html': 'text/html', '.js': 'text/javascript', '.mjs': 'text/javascript', '.json': 'application/json',
  '.gltf': 'model/gltf+json', '.bin': 'application/octet-stream', '.map': 'application/json' };

// Serves /web/ from this folder (the pages and node_modules) and /pack/ from the pack; nothing else.
function serve(pack) {
  const roots = { web: HERE, pack: path.resolve(pack) };
  const server = http.createServer((req, res) => {
    const url = new URL(req.url, 'http://localhost');
    const [, root, ...rest] = decodeURIComponent(url.pathname).split('/');
    const base = roots[root];
    const file = base && path.resolve(base, rest.join('/'));
    if (!file || !file.startsWith(base + path.sep) || !fs.existsSync(file) || !fs.statSync(file).isFile()) {
      res.writeHead(404);
      res.end();
      return;
    }
    res.writeHead(200, { 'Content-Type': TYPES[path.extname(file)] || 'application/octet-stream' });
    fs.createReadStream(file).pipe(res);
  });
  return new Promise((resolve) => server.listen(0, '127.0.0.1', () => resolve(server)));
}

async function main() {
  const a = parseArgs(process.argv.slice(2));
  const manifest = JSON.parse(fs.readFileSync(path.join(a.pack, 'manifest.json'), 'utf8'));
  const scenesOf = (job) => manifest.scenes.map((s) => s.name).filter((n) => !job.scenes || job.scenes.includes(n));
  const server = await serve(a.pack);
  const origin = `http://127.0.0.1:${server.address().port}`;
  // WebGPU on the CPU: Dawn on SwiftShader's Vulkan, which Chromium offers only when asked (the
  // adapter then reports vendor "google", architecture "swiftshader"). Only for a WebGPU run, so that
  // the WebGL2 runs' Chromium is started as it always was.
  const webgpu = a.backend === 'webgpu' && a.webgpuFlags
    ? ['--enable-unsafe-webgpu', '--use-webgpu-adapter=swiftshader', '--enable-features=Vulkan', '--use-vulkan=swiftshader',
      '--disable-vulkan-surface'] : [];
  const browser = await puppeteer.launch({
    executablePath: a.chromium || '/usr/bin/chromium',
    headless: true,
    args: [...webgpu,
      // WebGL2 on the CPU: ANGLE over SwiftShader's Vulkan, which headless Chromium otherwise
      // refuses as a fallback it considers unsafe for web content (ours is the local disk's).
      '--use-angle=swiftshader', '--enable-unsafe-swiftshader', '--ignore-gpu-blocklist',
      // A test machine runs this as root, where Chromium's sandbox cannot start.
      '--no-sandbox',
      // Nothing is fetched from the network: every request but the local server's fails.
      '--host-resolver-rules=MAP * ~NOTFOUND, EXCLUDE 127.0.0.1',
      '--disable-background-networking', '--no-first-run', '--disable-extensions',
    ],
  });
  let failed = false;
  try {
    const page = await browser.newPage();
    // The page's messages are held back until the backend is known to be the one asked for: a
    // refusal is one line (the engine's own fallback warning would only repeat it).
    let held = [];
    const say = (line) => (held ? held.push(line) : process.stderr.write(line));
    // Chromium asks for /favicon.ico, which the server does not have: not worth a line.
    page.on('console', (m) => {
      if ((m.type() === 'error' || m.type() === 'warn') && !m.text().startsWith('Failed to load resource')) say(`page: ${m.text()}\n`);
    });
    page.on('pageerror', (e) => say(`page error: ${e.message}\n`));
    page.on('response', (r) => { if (r.status() >= 400 && !r.url().endsWith('/favicon.ico')) say(`page: ${r.status()} ${r.url()}\n`); });
    // three.js's WebGPURenderer is in its WebGPU build, which its page maps 'three' to.
    const html = a.engine === 'three' && a.backend !== 'webgl2' ? 'three_webgpu' : a.engine;
    await page.goto(`${origin}/web/${html}.html`, { waitUntil: 'load' });
    await page.waitForFunction('window.harness !== undefined', { timeout: 60000 });
    // The browser's own version (the user agent string's is reduced to Chrome/x.0.0.0).
    const ready = await page.evaluate((backend, adapter, version) => window.harness.init(backend, adapter, version),
      a.backend, a.adapter, await browser.version());
    if (ready.error) {
      process.stderr.write(`render.mjs: ${ready.error}\n`);
      failed = true;
    } else {
      held.forEach((line) => process.stderr.write(line));
      held = null;
      process.stdout.write(`environment: ${JSON.stringify(ready.environment)}\n`);
    }
    const batched = a.jobs.length > 1;
    for (const job of ready.error ? [] : a.jobs) for (const scene of scenesOf(job)) {
      const t0 = Date.now();
      const r = await page.evaluate((url, variant) => window.harness.render(url, variant), `${origin}/pack/${scene}/scene.gltf`, job.variant);
      const named = batched ? `${job.variant}: ${scene}` : scene;
      if (r.error) {
        process.stderr.write(`${named}: ${r.error}\n`);
        failed = true;
        continue;
      }
      const dir = path.join(job.out, scene);
      fs.mkdirSync(dir, { recursive: true });
      r.masks.forEach((b64, i) => {
        const name = r.masks.length === 1 ? 'mask.png' : `mask_${i}.png`;
        fs.writeFileSync(path.join(dir, name), greyPng(r.width, r.height, Buffer.from(b64, 'base64')));
      });
      // A soft technique's lit fraction, per light with an area (visibility.png / visibility_<i>.png).
      (r.visibility ?? []).forEach(({ light, png }) => {
        const name = r.masks.length === 1 ? 'visibility.png' : `visibility_${light}.png`;
        fs.writeFileSync(path.join(dir, name), greyPng(r.width, r.height, Buffer.from(png, 'base64')));
      });
      fs.writeFileSync(path.join(dir, 'candidate.json'), JSON.stringify(r.candidate, null, 2) + '\n');
      process.stdout.write(`${named}: ${r.masks.length} mask(s), ${Date.now() - t0} ms\n`);
    }
  } finally {
    await browser.close();
    server.close();
  }
  process.exit(failed ? 1 : 0);
}

main().catch((e) => {
  process.stderr.write(`render.mjs: ${e.stack || e}\n`);
  process.exit(1);
});
