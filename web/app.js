// The editor page's entry (served by `intrinsic serve`, embedded with the
// other web/ files): loads the mesh from /api/mesh, wires the controls to the
// modules (api.js requests, view3d.js / view2d.js drawing, interact.js mouse,
// optimize.js lambda preview and optimizations) and asks for the first map.
// window.__intrinsic exposes the state for the browser test and the bench.
import { $, session, state } from './state.js';
import { failure, requestBody, solve } from './api.js';
import { clearConstraints, dragControls, finishLine, surfaceClick } from './interact.js';
import { fetchBasis, optimalLambda, optimizeBoundary, previewBlend } from './optimize.js';
import { draw } from './view.js';
import { handles } from './view2d.js';
import { cameraMatrices, init3d } from './view3d.js';

// uv(): the drawn UVs as [[u, v], ...].
const uvPairs = () => Array.from({ length: state.uv.length / 2 }, (_, i) => [state.uv[2 * i], state.uv[2 * i + 1]]);
window.__intrinsic = { session, state, handles, request: () => requestBody(), cameraMatrices, uv: uvPairs };

function downloadObj() {
  const m = state.mesh, uv = state.uv, lines = ['# intrinsic serve: ' + $('method').value + ', ' + $('boundary').value];
  for (let i = 0; i < m.vertices; i++) lines.push('v ' + m.positions.slice(3 * i, 3 * i + 3).join(' '));
  for (let i = 0; i < m.vertices; i++) lines.push('vt ' + uv[2 * i] + ' ' + uv[2 * i + 1]);
  for (let f = 0; f < m.triangles.length; f += 3) {
    const a = m.triangles[f] + 1, b = m.triangles[f + 1] + 1, c = m.triangles[f + 2] + 1;
    lines.push(`f ${a}/${a} ${b}/${b} ${c}/${c}`);
  }
  const link = document.createElement('a');
  link.href = URL.createObjectURL(new Blob([lines.join('\n') + '\n'], { type: 'text/plain' }));
  link.download = 'intrinsic.obj';
  link.click();
  URL.revokeObjectURL(link.href);
}

function controls() {
  const optionsChanged = () => {
    state.moves.clear();
    state.pins = null;
    state.selection = null;
    $('lambdaBox').style.display = $('method').value === 'mixed' ? '' : 'none';
    solve();
  };
  $('method').addEventListener('change', optionsChanged);
  $('boundary').addEventListener('change', optionsChanged);
  $('reset').addEventListener('click', optionsChanged);
  // The slider: a preview blend while it moves, the exact mixed map on release.
  // Both ends are fetched when the slider is taken (mouse or keyboard focus).
  for (const e of ['pointerdown', 'focus']) $('lambda').addEventListener(e, () => { fetchBasis().catch(() => {}); });
  $('lambda').addEventListener('input', (e) => previewBlend(e.timeStamp));
  $('lambda').addEventListener('change', () => solve());
  $('download').addEventListener('click', downloadObj);
  $('finishLine').addEventListener('click', finishLine);
  $('clearConstraints').addEventListener('click', clearConstraints);
  $('optimalLambda').addEventListener('click', optimalLambda);
  $('optimize').addEventListener('click', optimizeBoundary);
  $('colour').addEventListener('change', () => draw());
  $('falloff').addEventListener('input', () => { $('falloffValue').textContent = $('falloff').value; });
  window.addEventListener('resize', () => draw());
  $('lambdaBox').style.display = 'none';
}

async function main() {
  const res = await fetch('/api/mesh');
  if (!res.ok) { $('error').textContent = (await failure(res)).message; return; }
  state.mesh = await res.json();
  $('meshInfo').textContent = `${state.mesh.vertices} vertices, ${state.mesh.faces} faces`;
  controls();
  try { init3d(surfaceClick); } catch (e) { $('error').textContent = 'WebGL: ' + e.message; }
  dragControls();
  solve();
}

main();
