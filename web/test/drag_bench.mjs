// Server-side update time of a one-vertex drag through `intrinsic serve`
// (median of 50 moves, path "responses") and the HTTP round trip, as the page
// sees it. Usage: node drag_bench.mjs PATH/TO/intrinsic MESH
import { spawn } from 'node:child_process';
const [bin, mesh] = process.argv.slice(2);
const child = spawn(bin, ['serve', mesh, '--port', '0'], { stdio: ['ignore', 'pipe', 'inherit'] });
const url = await new Promise((res) => { let o = ''; child.stdout.on('data', (d) => { o += d; const m = o.match(/http:\/\/127\.0\.0\.1:\d+/); if (m) res(m[0]); }); });
const post = async (b) => { const t = performance.now(); const r = await fetch(url + '/api/solve', { method: 'POST', headers: { 'X-Session': 'bench' }, body: JSON.stringify(b) }); const j = await r.json(); return [j, performance.now() - t]; };
const m = await (await fetch(url + '/api/mesh')).json();
const [base, tf] = await post({});
console.log('vertices', m.vertices, 'boundary', m.boundary_loops[0].length, 'factor', base.update_ms.toFixed(1), 'ms, round trip', tf.toFixed(0));
const v = m.boundary_loops[0][17], p = base.uv[v];
const ms = [], rt = [], paths = {};
for (let i = 0; i < 50; i++) {
  const [a, t] = await post({ moves: [[v, p[0] + 0.001 * i, p[1] - 0.0005 * i]] });
  ms.push(a.update_ms); rt.push(t); paths[a.path] = (paths[a.path] || 0) + 1;
}
const med = (x) => x.slice().sort((a, b) => a - b)[x.length >> 1];
console.log('update_ms median', med(ms).toFixed(4), 'first', ms[0].toFixed(2), 'max', Math.max(...ms).toFixed(2), 'round trip median', med(rt).toFixed(1), 'ms', paths);
child.kill('SIGKILL');
