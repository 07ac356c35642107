// The page's loader and painter: instantiates dunas_web.wasm (no bindings generator), runs
// it at 60 steps a second, draws its draw list on a canvas that fills the window (its
// pixels the screen's, up to twice the CSS pixels), and turns the mouse or a finger into
// clicks (taps) and swipes. `window.dunas` exposes the game to the browser test.

// Record styles: the values of `Style` in web/src/draw_list.rs.
const SNOW = 0, ROPE = 1, PARTICLES = 2, HAND = 3, PENGUIN = 4, TRAIL = 5, TARGET = 6,
  SEA = 7, TRIANGLE = 8, SPAR = 9, HOOK = 10, ROOF = 11;
// The scenes, in `start`'s numbering.
const CATAPULT = 0, BOATS = 1, GRAPPLE = 2;
const BUTTONS = ['catapult', 'boats', 'grapple'];
const STEP_MS = 1000 / 60;
// A touch screen taps where a mouse clicks.
const TOUCH = matchMedia('(pointer: coarse)').matches || navigator.maxTouchPoints > 0;
const CLICK = TOUCH ? 'Tap' : 'Click';
const HELP = [
  `${CLICK} to let go of the penguin, swipe across the rope to cut it; ${CLICK.toLowerCase()} again once it lands.`,
  `${CLICK} to send a gust through the fleet.`,
  `${CLICK} a green hook to throw the rope to it; ${TOUCH ? 'hold a finger' : 'hold the button'} anywhere else to reel in and climb.`,
];

const canvas = document.getElementById('view');
const stage = document.getElementById('stage');
const ctx = canvas.getContext('2d');
const status = document.getElementById('status');
const showParticles = document.getElementById('particles');

const { instance } = await WebAssembly.instantiateStreaming(fetch('dunas_web.wasm'), {});
const wasm = instance.exports;

let scene = 0;
let length = 0;
// Canvas pixels a CSS pixel: line widths are given in CSS pixels.
let unit = 1;
// The cost of `frame()` (a step and its draw list), over the last 60 frames.
const costs = [];

// The canvas takes the stage's size in screen pixels (at most 2 a CSS pixel); the scene is
// told, and goes on framed anew.
function fit() {
  const r = stage.getBoundingClientRect();
  unit = Math.min(window.devicePixelRatio || 1, 2);
  const w = Math.max(1, Math.round(r.width * unit)), h = Math.max(1, Math.round(r.height * unit));
  if (w === canvas.width && h === canvas.height) return;
  canvas.width = w;
  canvas.height = h;
  wasm.resize(w, h);
  if (length > 0) draw();
}

function start(which) {
  scene = which;
  wasm.start(which, canvas.width, canvas.height);
  length = 0;
  costs.length = 0;
  BUTTONS.forEach((id, i) => document.getElementById(id).setAttribute('aria-pressed', String(which === i)));
  document.getElementById('help').textContent = HELP[which];
}

function frame() {
  const t0 = performance.now();
  length = wasm.frame();
  costs.push(performance.now() - t0);
  if (costs.length > 60) costs.shift();
}

function records() {
  const list = new Float32Array(wasm.memory.buffer, wasm.draw_list(), length);
  const out = [];
  for (let i = 0; i + 1 < list.length;) {
    const style = list[i], n = list[i + 1];
    out.push([style, list.subarray(i + 2, i + 2 + n)]);
    i += 2 + n;
  }
  return out;
}

function polyline(p) {
  ctx.beginPath();
  ctx.moveTo(p[0], p[1]);
  for (let i = 2; i + 1 < p.length; i += 2) ctx.lineTo(p[i], p[i + 1]);
  ctx.stroke();
}

// The canvas filled top to bottom from colour `top` to colour `bottom`.
function backdrop(top, bottom) {
  const g = ctx.createLinearGradient(0, 0, 0, canvas.height);
  g.addColorStop(0, top);
  g.addColorStop(1, bottom);
  ctx.fillStyle = g;
  ctx.fillRect(0, 0, canvas.width, canvas.height);
}

function winterSky() {
  backdrop('#6f9fd0', '#dfeaf5');
  // Far hills.
  ctx.fillStyle = '#c7d6e6';
  ctx.beginPath();
  ctx.moveTo(0, canvas.height * 0.8);
  for (let x = 0; x <= canvas.width; x += 40) {
    ctx.lineTo(x, canvas.height * (0.62 + 0.06 * Math.sin(x * 0.011) + 0.03 * Math.sin(x * 0.037)));
  }
  ctx.lineTo(canvas.width, canvas.height);
  ctx.lineTo(0, canvas.height);
  ctx.fill();
}

function sea(horizon, time) {
  const w = canvas.width, h = canvas.height;
  const sky = ctx.createLinearGradient(0, 0, 0, horizon);
  sky.addColorStop(0, '#7fb2e0');
  sky.addColorStop(1, '#cfe3f2');
  ctx.fillStyle = sky;
  ctx.fillRect(0, 0, w, horizon);
  const water = ctx.createLinearGradient(0, horizon, 0, h);
  water.addColorStop(0, '#3f86b0');
  water.addColorStop(1, '#12476e');
  ctx.fillStyle = water;
  ctx.fillRect(0, horizon, w, h - horizon);
  // Swell: crests that bunch up towards the horizon and roll in with time.
  ctx.strokeStyle = 'rgba(200, 230, 250, 0.35)';
  ctx.lineWidth = unit;
  for (let n = 1; n < 16; n++) {
    const d = n + ((time * 0.4) % 1);
    const y = horizon + (h - horizon) * (1 - 1 / (0.35 * d + 1)) * 1.25;
    const amp = (1 + 0.35 * d) * unit;
    ctx.beginPath();
    for (let x = 0; x <= w; x += 8) {
      const yy = y + amp * Math.sin(x * 0.05 / amp + time * 1.5 + n);
      if (x === 0) ctx.moveTo(x, yy); else ctx.lineTo(x, yy);
    }
    ctx.stroke();
  }
}

function penguin(x, y, r) {
  ctx.fillStyle = '#1b1f2a';
  ctx.beginPath();
  ctx.ellipse(x, y, r * 0.8, r, 0, 0, 2 * Math.PI);
  ctx.fill();
  ctx.fillStyle = '#f4f4f0';
  ctx.beginPath();
  ctx.ellipse(x, y + r * 0.15, r * 0.5, r * 0.75, 0, 0, 2 * Math.PI);
  ctx.fill();
  ctx.fillStyle = '#f29a1f';
  ctx.beginPath();
  ctx.moveTo(x - r * 0.15, y - r * 0.45);
  ctx.lineTo(x + r * 0.15, y - r * 0.45);
  ctx.lineTo(x, y - r * 0.25);
  ctx.fill();
  ctx.fillStyle = '#fff';
  for (const s of [-1, 1]) {
    ctx.beginPath();
    ctx.arc(x + s * r * 0.22, y - r * 0.6, r * 0.1, 0, 2 * Math.PI);
    ctx.fill();
  }
}

function draw() {
  const all = records();
  if (scene === CATAPULT) winterSky();
  // The cave: dusk light through its mouth.
  if (scene === GRAPPLE) backdrop('#2a3446', '#6a7b94');
  for (const [style, p] of all) {
    switch (style) {
      case SNOW:
        ctx.fillStyle = '#f7fbff';
        ctx.fillRect(0, p[1], canvas.width, canvas.height - p[1]);
        ctx.strokeStyle = '#b9cde0';
        ctx.lineWidth = 2 * unit;
        polyline(p);
        break;
      case ROPE:
        ctx.strokeStyle = '#7a5230';
        ctx.lineWidth = 5 * unit;
        ctx.lineCap = ctx.lineJoin = 'round';
        polyline(p);
        break;
      case PARTICLES:
        if (!showParticles.checked) break;
        ctx.strokeStyle = 'rgba(200, 40, 40, 0.8)';
        ctx.lineWidth = unit;
        polyline(p);
        ctx.fillStyle = '#c82828';
        for (let i = 0; i + 1 < p.length; i += 2) {
          ctx.beginPath();
          ctx.arc(p[i], p[i + 1], 3 * unit, 0, 2 * Math.PI);
          ctx.fill();
        }
        break;
      case HAND: {
        const [x, y, r, ox, oy] = p;
        // The tower, the arm that whirls the hand round its pivot, and the hand.
        ctx.fillStyle = '#6b4a2b';
        ctx.fillRect(ox - r * 0.6, oy, r * 1.2, canvas.height - oy);
        ctx.strokeStyle = '#8a6038';
        ctx.lineWidth = r * 0.8;
        ctx.lineCap = 'round';
        polyline([ox, oy, x, y]);
        ctx.fillStyle = '#d24d3a';
        ctx.beginPath();
        ctx.arc(x, y, r, 0, 2 * Math.PI);
        ctx.fill();
        break;
      }
      case PENGUIN:
        penguin(p[0], p[1], p[2]);
        break;
      case TRAIL:
        ctx.fillStyle = 'rgba(40, 60, 90, 0.5)';
        for (let i = 0; i + 1 < p.length; i += 4) {
          ctx.fillRect(p[i] - 1.5 * unit, p[i + 1] - 1.5 * unit, 3 * unit, 3 * unit);
        }
        break;
      case TARGET: {
        const u = unit;
        ctx.strokeStyle = '#2b6e2b';
        ctx.lineWidth = 2 * u;
        polyline([p[0], p[1], p[0], p[1] - 28 * u]);
        ctx.fillStyle = '#3c9a3c';
        ctx.beginPath();
        ctx.moveTo(p[0], p[1] - 28 * u);
        ctx.lineTo(p[0] + 16 * u, p[1] - 22 * u);
        ctx.lineTo(p[0], p[1] - 16 * u);
        ctx.fill();
        break;
      }
      case SEA:
        sea(p[0], p[1]);
        break;
      case TRIANGLE:
        ctx.fillStyle = `rgb(${p[6] | 0}, ${p[7] | 0}, ${p[8] | 0})`;
        ctx.beginPath();
        ctx.moveTo(p[0], p[1]);
        ctx.lineTo(p[2], p[3]);
        ctx.lineTo(p[4], p[5]);
        ctx.closePath();
        ctx.fill();
        // A hairline of the same colour hides the seams between triangles.
        ctx.strokeStyle = ctx.fillStyle;
        ctx.lineWidth = 0.6;
        ctx.stroke();
        break;
      case HOOK: {
        const [x, y, r, reach] = p;
        ctx.strokeStyle = reach ? '#46c35a' : '#8a8f96';
        ctx.lineWidth = Math.max(2 * unit, r * 0.45);
        ctx.beginPath();
        ctx.arc(x, y, r, 0, 2 * Math.PI);
        ctx.stroke();
        break;
      }
      case ROOF:
        ctx.fillStyle = '#3b3431';
        ctx.beginPath();
        ctx.moveTo(p[0], 0);
        for (let i = 0; i + 1 < p.length; i += 2) ctx.lineTo(p[i], p[i + 1]);
        ctx.lineTo(p[p.length - 2], 0);
        ctx.fill();
        break;
      case SPAR:
        ctx.strokeStyle = '#5a4632';
        ctx.lineWidth = p[4];
        ctx.lineCap = 'round';
        polyline(p.subarray(0, 4));
        break;
    }
  }
}

const mean = (v) => v.reduce((a, b) => a + b, 0) / Math.max(v.length, 1);

function report() {
  const t = wasm.time().toFixed(1);
  const cost = `frame ${mean(costs).toFixed(3)} ms (step + draw list, mean of the last ${costs.length})`;
  if (scene === BOATS) {
    status.textContent = `t = ${t} s · ${cost} · 9 sails of 8×8 particles, one solve a frame, drawn 12×12`;
    return;
  }
  if (scene === GRAPPLE) {
    const won = wasm.hook() === 7 && wasm.rope_length() <= 2 ? ' · on the last hook!' : '';
    status.textContent = `t = ${t} s · hook ${wasm.hook() + 1} of 8 · rope ${wasm.rope_length().toFixed(2)} m · ${cost} · 8 particles, links within ${(wasm.largest_off() * 100).toFixed(3)}% of the rope's length${won}`;
    return;
  }
  const states = ['whirling', 'flying', 'landed'];
  let line = `t = ${t} s · ${states[wasm.penguin()]} · ${cost} · largest stretch ${(wasm.largest_stretch() * 100).toFixed(2)}%`;
  if (wasm.pieces() > 1) line += ` · the rope is in ${wasm.pieces()} pieces`;
  if (wasm.penguin() === 2) {
    line += `\nlanded at x = ${wasm.landed_x().toFixed(3)} m; the closed-form arc from its release lands at ${wasm.arc_x().toFixed(3)} m`;
  }
  status.textContent = line;
}

let last = performance.now(), owed = 0;
function tick(now) {
  owed += Math.min(now - last, 100);
  last = now;
  // Paused (`window.dunas.paused`, for the browser test), the scene holds still and the
  // pointer still acts on it.
  if (window.dunas.paused) owed = 0;
  for (let n = 0; owed >= STEP_MS && n < 4; n++) {
    frame();
    owed -= STEP_MS;
  }
  owed = Math.min(owed, STEP_MS);
  if (length > 0) draw();
  report();
  requestAnimationFrame(tick);
}

// The pointer: a press and release that hardly moved is a click; a drag is a swipe, each
// move a stroke that cuts where it crosses the rope (once a swipe).
function at(event) {
  const r = canvas.getBoundingClientRect();
  return [(event.clientX - r.left) * canvas.width / r.width,
    (event.clientY - r.top) * canvas.height / r.height];
}
let press = null;
canvas.addEventListener('pointerdown', (e) => {
  press = { from: at(e), last: at(e), swiped: false, cut: false };
  canvas.setPointerCapture(e.pointerId);
  wasm.press(...press.from);
});
canvas.addEventListener('pointermove', (e) => {
  if (!press) return;
  const p = at(e);
  if (Math.hypot(p[0] - press.from[0], p[1] - press.from[1]) > 8 * unit) press.swiped = true;
  // A swipe cuts once: the first stroke that crosses the rope.
  if (press.swiped && !press.cut) press.cut = wasm.swipe(press.last[0], press.last[1], p[0], p[1]) === 1;
  press.last = p;
});
canvas.addEventListener('pointerup', () => {
  if (press && !press.swiped) wasm.click();
  wasm.lift();
  press = null;
});
canvas.addEventListener('pointercancel', () => {
  wasm.lift();
  press = null;
});
document.getElementById('catapult').addEventListener('click', () => start(0));
document.getElementById('boats').addEventListener('click', () => start(1));
document.getElementById('grapple').addEventListener('click', () => start(2));

window.dunas = {
  wasm,
  paused: false,
  scene: () => scene,
  // Hook `i` of the grappling hook in page coordinates.
  hookOnPage(i) {
    const r = canvas.getBoundingClientRect();
    return [r.left + wasm.hook_pixel(i, 0) * r.width / canvas.width,
      r.top + wasm.hook_pixel(i, 1) * r.height / canvas.height];
  },
  // The rope's particle `i` in page coordinates (for the test's swipe).
  particleOnPage(i) {
    const r = canvas.getBoundingClientRect();
    return [r.left + wasm.particle(i, 0) * r.width / canvas.width,
      r.top + wasm.particle(i, 1) * r.height / canvas.height];
  },
  // How many curves of rope the last frame drew.
  drawnPieces: () => records().filter(([style]) => style === ROPE).length,
  // The penguin's centre in page coordinates, as the last frame drew it.
  penguinOnPage() {
    const r = canvas.getBoundingClientRect();
    const found = records().find(([style]) => style === PENGUIN);
    return found && [r.left + found[1][0] * r.width / canvas.width,
      r.top + found[1][1] * r.height / canvas.height];
  },
  // Mean ms of a frame over `frames` frames of a fresh catapult game, in this browser.
  bench(frames) {
    const t0 = performance.now();
    wasm.bench_catapult(frames);
    return (performance.now() - t0) / frames;
  },
  frameCost: () => mean(costs),
};

fit();
start(0);
new ResizeObserver(fit).observe(stage);
requestAnimationFrame(tick);
