// Browser test of `intrinsic serve` (registered in CTest when node, Debian's
// /usr/bin/chromium and this folder's node_modules exist): opens the editor in
// headless Chromium at the printed URL (with its token; the page then works
// through the cookie, and the server refuses requests without the token or
// from another origin), drags a boundary handle of the 2D layout with real mouse
// events, waits for the update, reads the UVs back through the API (same
// session) and compares them with `intrinsic param --boundary FILE` for the
// dragged position (1e-9); then, with the "click on surface" tool, clicks the
// 3D view to add a point constraint, drags its target in the layout, and
// compares the UVs again with `intrinsic param --boundary FILE --constraints
// FILE` (and checks the session kept one factorization); then drags a
// shift-click-selected boundary range with falloff and compares again; then checks a
// screenshot (angle distortion colouring on) is not blank; then switches to
// the natural map, drags a pin and compares with `intrinsic param --pin`.
// Usage: node browser_test.mjs PATH/TO/intrinsic MESH|generated
// "generated": a wavy patch written by `intrinsic generate` (nothing needed
// beside the repository). A MESH whose folder is absent (../shared beside a
// clone alone) exits 77, which ctest reports as Skipped.
import { spawn, execFileSync } from 'node:child_process';
import fs from 'node:fs';
import os from 'node:os';
import path from 'node:path';
import { chromium } from 'playwright-core';

const [binary, meshArg] = process.argv.slice(2);
if (!binary || !meshArg) {
  console.error('usage: node browser_test.mjs INTRINSIC MESH|generated');
  process.exit(2);
}
if (meshArg !== 'generated' && !fs.existsSync(path.dirname(meshArg))) {
  console.log(`SKIPPED: ${path.dirname(meshArg)} is absent (the shared meshes are not beside this clone)`);
  process.exit(77);
}
const meshDir = meshArg === 'generated' ? fs.mkdtempSync(path.join(os.tmpdir(), 'intrinsic-browser-mesh-')) : null;
const mesh = meshDir ? path.join(meshDir, 'wave.obj') : meshArg;
if (meshDir) execFileSync(binary, ['generate', 'wave', '--rings', '8', '-o', mesh]);

// Starts the server on a free port; resolves with the URL it prints
// (http://127.0.0.1:PORT/?token=HEX: the page's first load needs the token).
function startServer() {
  const child = spawn(binary, ['serve', mesh, '--port', '0'], { stdio: ['ignore', 'pipe', 'inherit'] });
  const url = new Promise((resolve, reject) => {
    let out = '';
    child.stdout.on('data', (d) => {
      out += d;
      const m = out.match(/http:\/\/127\.0\.0\.1:\d+\/\?token=[0-9a-f]+/);
      if (m) resolve(m[0]);
    });
    child.on('exit', (code) => reject(new Error('intrinsic serve exited with ' + code)));
    setTimeout(() => reject(new Error('intrinsic serve printed no URL')), 60000).unref();
  });
  return { child, url };
}

// The API from node: no cookie here, so the token goes in the header.
async function api(url, route, body, session) {
  const u = new URL(url), token = { 'X-Intrinsic-Token': u.searchParams.get('token') };
  const res = await fetch(u.origin + route, body === undefined ? { headers: token } : {
    method: 'POST', headers: { ...token, 'Content-Type': 'application/json', 'X-Session': session }, body: JSON.stringify(body),
  });
  if (!res.ok) throw new Error(`${route}: HTTP ${res.status} ${await res.text()}`);
  return res.json();
}

// Per-vertex UVs of an OBJ written by `intrinsic param`.
function objUV(file, n) {
  const vt = [], uv = new Array(n).fill(null);
  for (const line of fs.readFileSync(file, 'utf8').split('\n')) {
    const w = line.trim().split(/\s+/);
    if (w[0] === 'vt') vt.push([Number(w[1]), Number(w[2])]);
    if (w[0] === 'f') for (const c of w.slice(1)) { const [v, t] = c.split('/').map(Number); uv[v - 1] = vt[t - 1]; }
  }
  return uv;
}

function maxDiff(a, b) {
  let d = 0;
  for (let i = 0; i < a.length; i++) if (b[i]) d = Math.max(d, Math.abs(a[i][0] - b[i][0]), Math.abs(a[i][1] - b[i][1]));
  return d;
}

// Standard deviation of the grey levels of a PNG, decoded by the page itself.
async function pixelSpread(page, png) {
  return page.evaluate(async (b64) => {
    const img = new Image();
    img.src = 'data:image/png;base64,' + b64;
    await img.decode();
    const c = document.createElement('canvas');
    c.width = img.width; c.height = img.height;
    const ctx = c.getContext('2d');
    ctx.drawImage(img, 0, 0);
    const d = ctx.getImageData(0, 0, c.width, c.height).data;
    let s = 0, s2 = 0, n = 0;
    for (let i = 0; i < d.length; i += 4) { const g = (d[i] + d[i + 1] + d[i + 2]) / 3; s += g; s2 += g * g; n++; }
    return Math.sqrt(Math.max(0, s2 / n - (s / n) ** 2));
  }, png.toString('base64'));
}

async function dragHandle(page) {
  const handles = await page.evaluate(() => window.__intrinsic.handles());
  if (!handles.length) throw new Error('no boundary handles on the page');
  const h = handles[Math.floor(handles.length / 3)];
  const before = await page.evaluate(() => window.__intrinsic.state.updates);
  await page.mouse.move(h.x, h.y);
  await page.mouse.down();
  await page.mouse.move(h.x + 25, h.y - 15, { steps: 6 });
  await page.mouse.move(h.x + 40, h.y - 30, { steps: 6 });
  await page.mouse.up();
  await page.waitForFunction((n) => {
    const s = window.__intrinsic.state;
    return s.updates > n && !s.inFlight && !s.queued && s.moves.size > 0;
  }, before, { timeout: 30000 });
  return h.vertex;
}

// Client position of the centroid of the face whose projection is nearest the 3D view's centre.
async function surfacePoint(page) {
  return page.evaluate(() => {
    const { state, cameraMatrices } = window.__intrinsic;
    const canvas = document.getElementById('view3d'), rect = canvas.getBoundingClientRect();
    const { mvp } = cameraMatrices(canvas.width / canvas.height);
    const m = state.mesh, tri = m.triangles, pos = m.positions;
    let best = null, bestD = Infinity;
    for (let f = 0; f < tri.length / 3; f++) {
      let X = 0, Y = 0, Z = 0;
      for (let k = 0; k < 3; k++) { X += pos[3 * tri[3 * f + k]] / 3; Y += pos[3 * tri[3 * f + k] + 1] / 3; Z += pos[3 * tri[3 * f + k] + 2] / 3; }
      const w = mvp[3] * X + mvp[7] * Y + mvp[11] * Z + mvp[15];
      const x = (mvp[0] * X + mvp[4] * Y + mvp[8] * Z + mvp[12]) / w, y = (mvp[1] * X + mvp[5] * Y + mvp[9] * Z + mvp[13]) / w;
      const d = Math.hypot(x, y);
      if (d < bestD) { bestD = d; best = [rect.left + (x + 1) / 2 * rect.width, rect.top + (1 - y) / 2 * rect.height]; }
    }
    return best;
  });
}

const settled = (n) => {
  const s = window.__intrinsic.state;
  return s.updates > n && !s.inFlight && !s.queued;
};

// Clicks the surface (point constraint tool), waits, then drags the new target in the layout.
async function addAndDragConstraint(page) {
  await page.selectOption('#click3d', 'point');
  const [x, y] = await surfacePoint(page);
  const uvBefore = await page.evaluate(() => window.__intrinsic.uv());
  let before = await page.evaluate(() => window.__intrinsic.state.updates);
  await page.mouse.click(x, y);
  await page.waitForFunction(settled, before, { timeout: 30000 });
  const added = await page.evaluate(() => ({ n: window.__intrinsic.state.constraints.points.length, path: window.__intrinsic.state.answer.path }));
  if (added.n !== 1 || added.path !== 'constraints') throw new Error('clicking the surface added no constraint: ' + JSON.stringify(added));
  const target = (await page.evaluate(() => window.__intrinsic.handles())).find((h) => h.kind === 'point');
  before = await page.evaluate(() => window.__intrinsic.state.updates);
  await page.mouse.move(target.x, target.y);
  await page.mouse.down();
  await page.mouse.move(target.x + 12, target.y + 8, { steps: 5 });
  await page.mouse.up();
  await page.waitForFunction(settled, before, { timeout: 30000 });
  const answer = await page.evaluate(() => ({ path: window.__intrinsic.state.answer.path, factorizations: window.__intrinsic.state.answer.factorizations }));
  // The last answer is either the drag's own or the exact float64 answer
  // the page asks for on release, which the server gives from the same
  // state: both through the editor's responses (the target's response, or
  // nothing left to move), on the one factorization.
  if (answer.path !== 'responses' || answer.factorizations !== 1)
    throw new Error('dragging the target: ' + JSON.stringify(answer));
  const moved = maxDiff(uvBefore, await page.evaluate(() => window.__intrinsic.uv()));
  console.log(`the dragged constraint target moved the map by up to ${moved}`);
  if (!(moved > 1e-4)) throw new Error('dragging the constraint target did not change the map');
}

// Shift-clicks two boundary handles (a range), sets the falloff, drags the range's middle.
async function dragRange(page) {
  const b = (await page.evaluate(() => window.__intrinsic.handles())).filter((h) => h.kind === 'boundary');
  const n = b.length, at = (i) => b[((i % n) + n) % n], k = Math.floor((2 * n) / 3);
  if (n < 12) throw new Error('the range drag needs at least 12 boundary vertices');
  await page.keyboard.down('Shift');
  await page.mouse.click(at(k).x, at(k).y);
  await page.mouse.click(at(k + 4).x, at(k + 4).y);
  await page.keyboard.up('Shift');
  await page.evaluate(() => { document.getElementById('falloff').value = '3'; });
  const before = await page.evaluate(() => window.__intrinsic.state.updates);
  await page.mouse.move(at(k + 2).x, at(k + 2).y);
  await page.mouse.down();
  await page.mouse.move(at(k + 2).x - 15, at(k + 2).y + 10, { steps: 5 });
  await page.mouse.up();
  await page.waitForFunction(settled, before, { timeout: 30000 });
  const range = Array.from({ length: 11 }, (_, i) => at(k - 3 + i).vertex);
  const moved = await page.evaluate(() => Array.from(window.__intrinsic.state.moves.keys()));
  if (!range.every((v) => moved.includes(v))) throw new Error('the range and its falloff did not all move');
}

// Writes the request's boundary (moves over the unmoved base) and constraints, runs `intrinsic param`.
function paramFor(request, base, meshInfo, dir) {
  const moved = new Map((request.moves || []).map((m) => [m[0], [m[1], m[2]]]));
  const lines = meshInfo.boundary_loops[0].map((v) => {
    const p = moved.get(v) || base.uv[v];
    return `${v} ${p[0]} ${p[1]}`;
  });
  fs.writeFileSync(path.join(dir, 'b.txt'), lines.join('\n') + '\n');
  const args = ['param', mesh, '--boundary', path.join(dir, 'b.txt'), '-o', path.join(dir, 'out.obj'), '-q'];
  if (request.constraints) {
    fs.writeFileSync(path.join(dir, 'c.json'), JSON.stringify(request.constraints));
    args.push('--constraints', path.join(dir, 'c.json'));
  }
  execFileSync(binary, args);
  return objUV(path.join(dir, 'out.obj'), meshInfo.vertices);
}

// Natural map: switches the boundary to natural (the constraint stays),
// drags a pin with real mouse events, and compares the served and the
// page's UVs with `intrinsic param --boundary natural --pin ...`.
async function dragPin(page, url, meshInfo, dir) {
  let before = await page.evaluate(() => window.__intrinsic.state.updates);
  await page.selectOption('#boundary', 'natural');
  await page.waitForFunction(settled, before, { timeout: 60000 });
  const pin = (await page.evaluate(() => window.__intrinsic.handles())).find((h) => h.kind === 'pin');
  if (!pin) throw new Error('no pin handles in the natural map');
  const uvBefore = await page.evaluate(() => window.__intrinsic.uv());
  before = await page.evaluate(() => window.__intrinsic.state.updates);
  await page.mouse.move(pin.x, pin.y);
  await page.mouse.down();
  await page.mouse.move(pin.x + 20, pin.y - 12, { steps: 5 });
  await page.mouse.up();
  await page.waitForFunction(settled, before, { timeout: 30000 });
  const { session, request, pageUV, answer } = await page.evaluate(() => ({
    session: window.__intrinsic.session, request: window.__intrinsic.request(), pageUV: window.__intrinsic.uv(),
    answer: { path: window.__intrinsic.state.answer.path, factorizations: window.__intrinsic.state.answer.factorizations },
  }));
  // Default pins, then the same pins dragged: one factorization, the pins' responses.
  if (answer.path !== 'responses' || answer.factorizations !== 1) throw new Error('dragging the pin: ' + JSON.stringify(answer));
  if (!request.pins || !request.pins.some((p) => p[0] === pin.vertex)) throw new Error('the dragged pin is not in the request');
  const moved = maxDiff(uvBefore, pageUV);
  if (!(moved > 1e-4)) throw new Error('dragging the pin did not change the map');
  const served = await api(url, '/api/solve', request, session);
  if (served.path !== 'responses') throw new Error('expected the editor path, got ' + served.path);
  const args = ['param', mesh, '--boundary', 'natural', '-o', path.join(dir, 'out.obj'), '-q'];
  for (const p of request.pins) args.push('--pin', `${p[0]}:${p[1]},${p[2]}`);
  if (request.constraints) {
    fs.writeFileSync(path.join(dir, 'c.json'), JSON.stringify(request.constraints));
    args.push('--constraints', path.join(dir, 'c.json'));
  }
  execFileSync(binary, args);
  const cli = objUV(path.join(dir, 'out.obj'), meshInfo.vertices);
  const dServed = maxDiff(served.uv, cli), dPage = maxDiff(pageUV, cli);
  console.log(`pin ${pin.vertex} dragged (natural map): moved the map by up to ${moved}; |served - param| = ${dServed}, |page - param| = ${dPage}`);
  if (!(dServed < 1e-9) || !(dPage < 1e-9)) throw new Error('served UVs differ from intrinsic param --pin');
}

async function compareWithParam(page, url, base, meshInfo, dir, what) {
  const { session, request, pageUV } = await page.evaluate(() => ({
    session: window.__intrinsic.session, request: window.__intrinsic.request(),
    pageUV: window.__intrinsic.uv(),
  }));
  const served = await api(url, '/api/solve', request, session);
  if (served.path !== 'responses') throw new Error('expected the editor path, got ' + served.path);
  const cli = paramFor(request, base, meshInfo, dir);
  const dServed = maxDiff(served.uv, cli), dPage = maxDiff(pageUV, cli);
  console.log(`${what}: |served - param| = ${dServed}, |page - param| = ${dPage}`);
  if (!(dServed < 1e-9) || !(dPage < 1e-9)) throw new Error('served UVs differ from intrinsic param');
  return request;
}

// The page works through the cookie its first load got (HttpOnly: no
// script sees it); without the token, and from another origin, the server refuses.
async function checkGuard(page, url) {
  const origin = new URL(url).origin;
  const seen = await page.evaluate(async () => ({
    cookie: document.cookie, mesh: (await fetch('/api/mesh')).status, page: (await fetch('/')).status,
  }));
  if (seen.cookie !== '' || seen.mesh !== 200 || seen.page !== 200) throw new Error('the page with its cookie: ' + JSON.stringify(seen));
  const bare = await fetch(origin + '/api/mesh'), noPage = await fetch(origin + '/');
  const foreign = await fetch(url, { headers: { Origin: 'http://evil.example' } });
  if (bare.status !== 403 || noPage.status !== 403 || foreign.status !== 403) {
    throw new Error(`without token / foreign origin: ${bare.status} ${noPage.status} ${foreign.status}`);
  }
  console.log('guard: the page reads the API through its HttpOnly cookie; no token or a foreign Origin: 403');
}

async function main() {
  const { child, url: urlPromise } = startServer();
  let browser = null;
  const dir = fs.mkdtempSync(path.join(os.tmpdir(), 'intrinsic-browser-'));
  try {
    const url = await urlPromise;
    browser = await chromium.launch({
      executablePath: '/usr/bin/chromium', headless: true,
      args: ['--no-sandbox', '--enable-unsafe-swiftshader', '--use-angle=swiftshader', '--ignore-gpu-blocklist'],
    });
    const page = await browser.newPage({ viewport: { width: 1280, height: 800 } });
    page.on('pageerror', (e) => console.error('page error:', e.message));
    await page.goto(url);
    await page.waitForFunction(() => window.__intrinsic && window.__intrinsic.state.updates >= 1 &&
      window.__intrinsic.state.frames >= 1, null, { timeout: 60000 });
    await checkGuard(page, url);
    const vertex = await dragHandle(page);
    const meshInfo = await api(url, '/api/mesh');
    const base = await api(url, '/api/solve', {}, 'browser-test-base');
    const request = await compareWithParam(page, url, base, meshInfo, dir, `dragged vertex ${vertex}`);
    if (!request.moves.some((m) => m[0] === vertex)) throw new Error('the dragged vertex was not moved');
    await addAndDragConstraint(page);
    await compareWithParam(page, url, base, meshInfo, dir, 'point constraint added on the surface, target dragged');
    await dragRange(page);
    await compareWithParam(page, url, base, meshInfo, dir, 'boundary range (5 vertices, falloff 3) dragged');

    await page.selectOption('#colour', 'angle');
    await page.waitForTimeout(300);
    const shot = await page.screenshot({ path: path.join(os.tmpdir(), 'intrinsic-editor.png') });
    const spread = await pixelSpread(page, shot);
    const box = await page.locator('#view3d').boundingBox();
    const spread3d = await pixelSpread(page, await page.screenshot({ clip: box }));
    console.log(`screenshot grey-level spread: page ${spread.toFixed(1)}, 3D view ${spread3d.toFixed(1)}`);
    if (!(spread > 5)) throw new Error('the screenshot is blank');
    if (!(spread3d > 5)) throw new Error('the 3D view is blank');
    await dragPin(page, url, meshInfo, dir);
    console.log('browser test passed');
  } finally {
    if (browser) await browser.close();
    child.kill('SIGKILL');
    fs.rmSync(dir, { recursive: true, force: true });
    if (meshDir) fs.rmSync(meshDir, { recursive: true, force: true });
  }
}

main().catch((e) => {
  console.error('browser test failed:', e.message);
  process.exit(1);
});
