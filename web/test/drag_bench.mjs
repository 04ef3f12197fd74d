// Drag timings of `intrinsic serve` (a bench, never asserted anywhere).
// Server: the update time of a one-vertex drag (update_ms, path "responses")
// and the HTTP round trip, median of RUNS moves. Browser (headless Debian
// chromium through playwright-core, as the browser test): a boundary handle
// held with real mouse events, RUNS moves one after another, each measured
// in the page from the mouse event's timestamp to the requestAnimationFrame
// after the frame that drew its new UVs (state.latencies, view.js).
// Usage: node drag_bench.mjs PATH/TO/intrinsic MESH [RUNS]
import { spawn } from 'node:child_process';
import { chromium } from 'playwright-core';

const [bin, mesh, runsArg] = process.argv.slice(2);
const runs = Number(runsArg || 50);
const child = spawn(bin, ['serve', mesh, '--port', '0'], { stdio: ['ignore', 'pipe', 'inherit'] });
// The printed URL holds the token: the page gets its cookie from it, node's fetches send it as a header.
const printed = await new Promise((res) => { let o = ''; child.stdout.on('data', (d) => { o += d; const m = o.match(/http:\/\/127\.0\.0\.1:\d+\/\?token=[0-9a-f]+/); if (m) res(new URL(m[0])); }); });
const url = printed.origin, token = { 'X-Intrinsic-Token': printed.searchParams.get('token') };
const med = (x) => x.slice().sort((a, b) => a - b)[x.length >> 1];
const post = async (b) => {
  const t = performance.now();
  const r = await fetch(url + '/api/solve', { method: 'POST', headers: { ...token, 'X-Session': 'bench' }, body: JSON.stringify(b) });
  const j = await r.json();
  return [j, performance.now() - t];
};

async function serverSide() {
  const m = await (await fetch(url + '/api/mesh', { headers: token })).json();
  const [base, tf] = await post({});
  console.log('vertices', m.vertices, 'boundary', m.boundary_loops[0].length, 'factor', base.update_ms.toFixed(1), 'ms, round trip', tf.toFixed(0), 'ms');
  const v = m.boundary_loops[0][17], p = base.uv[v];
  const ms = [], rt = [], paths = {};
  for (let i = 0; i < runs; i++) {
    const [a, t] = await post({ moves: [[v, p[0] + 0.001 * i, p[1] - 0.0005 * i]] });
    ms.push(a.update_ms); rt.push(t); paths[a.path] = (paths[a.path] || 0) + 1;
  }
  console.log(`server: update_ms median ${med(ms).toFixed(4)} (first ${ms[0].toFixed(2)}, max ${Math.max(...ms).toFixed(2)}), ` +
    `round trip median ${med(rt).toFixed(1)} ms over ${runs} moves`, paths);
}

async function browserSide() {
  const browser = await chromium.launch({
    executablePath: '/usr/bin/chromium', headless: true,
    args: ['--no-sandbox', '--enable-unsafe-swiftshader', '--use-angle=swiftshader', '--ignore-gpu-blocklist'],
  });
  try {
    const page = await browser.newPage({ viewport: { width: 1280, height: 800 } });
    await page.goto(printed.href);
    await page.waitForFunction(() => window.__intrinsic && window.__intrinsic.state.frames >= 1 && window.__intrinsic.state.updates >= 1, null, { timeout: 120000 });
    const hs = await page.evaluate(() => window.__intrinsic.handles());
    const h = hs[Math.floor(hs.length / 3)];
    // Second pass with the 3D view hidden: what the WebGL draw (software, SwiftShader, when headless) costs.
    for (const pass of ['3D and 2D views', '2D view only']) {
      if (pass === '2D view only') await page.evaluate(() => { document.getElementById('view3d').style.display = 'none'; });
      const start = await page.evaluate(() => window.__intrinsic.state.latencies.length);
      const startRt = await page.evaluate(() => window.__intrinsic.state.roundTrips.length);
      const startDraw = await page.evaluate(() => window.__intrinsic.state.drawTimes.length);
      const startUp = await page.evaluate(() => (window.__intrinsic.state.uploadTimes || []).length);
      await page.mouse.move(h.x, h.y);
      await page.mouse.down();
      for (let i = 1; i <= runs + 3; i++) {
        const n = await page.evaluate(() => window.__intrinsic.state.latencies.length);
        await page.mouse.move(h.x + (i % 20), h.y - (i % 13));
        await page.waitForFunction((k) => window.__intrinsic.state.latencies.length > k, n, { timeout: 60000 });
      }
      await page.mouse.up();
      const lat = (await page.evaluate(() => window.__intrinsic.state.latencies)).slice(start + 3);  // the first moves compute responses
      const rt = (await page.evaluate(() => window.__intrinsic.state.roundTrips)).slice(startRt + 3);
      const dt = (await page.evaluate(() => window.__intrinsic.state.drawTimes)).slice(startDraw + 3);
      const ph = (await page.evaluate(() => window.__intrinsic.state.phases || [])).slice(startRt + 3);
      const up = (await page.evaluate(() => window.__intrinsic.state.uploadTimes || [])).slice(startUp + 3);
      const m = (k) => med(ph.map((p) => p[k])).toFixed(2);
      console.log(`browser (${pass}): mouse event to frame median ${med(lat).toFixed(1)} ms (min ${Math.min(...lat).toFixed(1)}, ` +
        `max ${Math.max(...lat).toFixed(1)}) over ${lat.length} moves; of which request to parsed answer median ${med(rt).toFixed(1)} ms, ` +
        `frame callback (uploads, overlay, GL calls) median ${med(dt).toFixed(1)} ms`);
      if (ph.length) console.log(`  medians: event to request sent ${m('wait')} ms, request to headers ${m('headers')} ms (server update ${m('server')} ms), ` +
        `body (UVs) ${m('body')} ms, buffer uploads ${med(up).toFixed(2)} ms, frame callback without uploads ${(med(dt) - med(up)).toFixed(2)} ms`);
    }
  } finally {
    await browser.close();
  }
}

try {
  await serverSide();
  await browserSide();
} finally {
  child.kill('SIGKILL');
}
