// The lambda slider's preview and the optimizations of paper section 5.
// Preview: while the slider moves, the page shows lambda U_conformal +
// (1 - lambda) U_authalic, both solved by the server for the current
// boundary and constraints (each in its own session, so the tab's
// factorization is kept). That blend of solutions is the paper's line of
// maps (section 5.1, docs/maths.md §7.1), NOT the mixed map of the weights
// lambda, 1 - lambda (§1.5): it is labelled as a preview, and the exact mixed
// map is solved when the slider is released. Optimal lambda returns a map on
// that same line. Boundary optimization runs as one request while the page
// polls its energies and draws the curve.
import { $, natural, session, state } from './state.js';
import { post, requestBody, setError, show } from './api.js';
import { draw } from './view.js';

let basis = null;  // {key, conformal: Float64Array, authalic: Float64Array}

function basisBody(method) {
  const body = requestBody(method);
  delete body.lambda;
  delete body.mu;
  return body;
}

const flat = (uv) => { const a = new Float64Array(2 * uv.length); uv.forEach((p, i) => { a[2 * i] = p[0]; a[2 * i + 1] = p[1]; }); return a; };

// Solves both ends of the line for the current state (once per state).
export async function fetchBasis() {
  if (natural()) return;  // the authalic map has no natural boundary
  const key = JSON.stringify(basisBody('conformal'));
  if (basis && basis.key === key) return;
  const [c, a] = await Promise.all([post('/api/solve', basisBody('conformal'), session + '-c'),
    post('/api/solve', basisBody('authalic'), session + '-a')]);
  basis = { key, conformal: flat(c.uv), authalic: flat(a.uv) };
}

export function previewBlend(stamp) {
  const lambda = Number($('lambda').value);
  $('lambdaValue').textContent = lambda.toFixed(2);
  if (!basis || basis.key !== JSON.stringify(basisBody('conformal'))) return;
  const uv = new Float64Array(basis.conformal.length);
  for (let i = 0; i < uv.length; i++) uv[i] = lambda * basis.conformal[i] + (1 - lambda) * basis.authalic[i];
  state.uv = uv;
  state.preview = { label: `preview: blend ${lambda.toFixed(2)} conformal + ${(1 - lambda).toFixed(2)} authalic (release to solve the mixed map)` };
  $('path').textContent = 'preview blend';
  draw(stamp);
}

export async function optimalLambda() {
  try {
    const body = requestBody();
    delete body.constraints;
    body.energy = $('lambdaEnergy').value;
    const t0 = performance.now();
    const answer = await post('/api/optimal_lambda', body);
    $('method').value = 'mixed';
    $('lambdaBox').style.display = '';
    $('lambda').value = answer.lambda;
    $('lambdaValue').textContent = answer.lambda.toFixed(3);
    state.preview = { label: `optimal ${body.energy} lambda* = ${answer.lambda.toFixed(4)}: the blend of solutions at lambda* (move anything to solve the mixed map)` };
    show(answer, performance.now() - t0);
    setError(null);
  } catch (e) { setError(e); }
}

export async function optimizeBoundary() {
  const body = requestBody();
  delete body.constraints;
  body.energy = $('boundaryEnergy').value;
  body.max_iterations = Number($('iterations').value);
  const energies = [];
  let running = true;
  const poll = async () => {
    while (running) {
      try {
        const res = await fetch('/api/optimize_boundary/progress', { headers: { 'X-Session': session } });
        const p = await res.json();
        if (p.energies) { energies.length = 0; energies.push(...p.energies); drawCurve(energies); }
      } catch (e) { /* the optimization's own request reports errors */ }
      await new Promise((r) => setTimeout(r, 150));
    }
  };
  $('optimize').disabled = true;
  poll();
  try {
    const t0 = performance.now();
    const answer = await post('/api/optimize_boundary', body);
    running = false;
    drawCurve(answer.energy_history);
    $('curveInfo').textContent = `${answer.iterations} iterations, ${answer.stop_reason}; energy ` +
      `${answer.energy_history[0].toPrecision(4)} → ${answer.energy_history[answer.energy_history.length - 1].toPrecision(4)}`;
    // Later drags start from the optimized boundary.
    state.moves.clear();
    for (const v of state.mesh.boundary_loops[0]) state.moves.set(v, answer.uv[v].slice());
    state.preview = null;
    show(answer, performance.now() - t0);
    setError(null);
  } catch (e) { setError(e); } finally {
    running = false;
    $('optimize').disabled = false;
  }
}

function drawCurve(energies) {
  const c = $('curve'), ctx = c.getContext('2d');
  c.width = c.clientWidth; c.height = c.clientHeight;
  ctx.clearRect(0, 0, c.width, c.height);
  if (energies.length < 1) return;
  const lo = Math.min(...energies), hi = Math.max(...energies), span = hi - lo || 1;
  ctx.strokeStyle = '#1f5fbf';
  ctx.lineWidth = 1.5;
  ctx.beginPath();
  energies.forEach((e, k) => {
    const x = 4 + (c.width - 8) * (energies.length > 1 ? k / (energies.length - 1) : 0), y = 4 + (c.height - 8) * (hi - e) / span;
    k ? ctx.lineTo(x, y) : ctx.moveTo(x, y);
  });
  ctx.stroke();
  ctx.fillStyle = '#444';
  ctx.font = '10px system-ui, sans-serif';
  ctx.fillText(`E ${energies[energies.length - 1].toPrecision(4)} (it ${energies.length})`, 6, 12);
}

