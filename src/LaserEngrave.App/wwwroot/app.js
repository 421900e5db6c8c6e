// LaserEngrave page: shows the view-models' state (pushed over Server-Sent Events) and sends the user's changes.
'use strict';

const $ = (id) => document.getElementById(id);
let state = null;

// ---- talking to the server -------------------------------------------------------------------------------------
async function post(path, body, raw) {
  const headers = { 'X-LaserEngrave': '1' };
  if (!raw) headers['Content-Type'] = 'application/json';
  const response = await fetch(path, { method: 'POST', headers, body: raw ? body : JSON.stringify(body ?? {}) });
  let json = null;
  try { json = await response.json(); } catch { /* some answers have no body */ }
  if (json && json.state) { apply(json.state); } else if (json && json.settings) { apply(json); }
  return { ok: response.ok, json };
}

function connectEvents() {
  const events = new EventSource('/api/events');
  events.onmessage = (e) => apply(JSON.parse(e.data));
  events.onerror = () => { $('status-machine').textContent = 'server not reachable; retrying…'; };
}

// ---- views ---------------------------------------------------------------------------------------------------------
let currentView = 'image';
function showView(name) {
  currentView = name;
  document.querySelectorAll('#nav button').forEach((b) => b.classList.toggle('active', b.dataset.view === name));
  document.querySelectorAll('.view').forEach((v) => v.classList.toggle('active', v.id === 'view-' + name));
  if (name === 'preview') { resizeCanvases(); if (!view.fitted) fit('job'); draw(); }
  location.hash = name;
}
document.querySelectorAll('#nav button').forEach((b) => b.addEventListener('click', () => showView(b.dataset.view)));

// ---- image: upload, drag and drop, recent files ----------------------------------------------------------------------
async function upload(file) {
  await post('/api/image?name=' + encodeURIComponent(file.name), file, true);
}
$('file').addEventListener('change', (e) => { if (e.target.files[0]) upload(e.target.files[0]); e.target.value = ''; });
const drop = $('drop');
['dragenter', 'dragover'].forEach((n) => drop.addEventListener(n, (e) => { e.preventDefault(); drop.classList.add('over'); }));
['dragleave', 'drop'].forEach((n) => drop.addEventListener(n, (e) => { e.preventDefault(); drop.classList.remove('over'); }));
drop.addEventListener('drop', (e) => { const f = e.dataTransfer.files[0]; if (f) upload(f); });
document.addEventListener('dragover', (e) => e.preventDefault());
document.addEventListener('drop', (e) => { e.preventDefault(); const f = e.dataTransfer?.files[0]; if (f) { showView('image'); upload(f); } });
$('open-recent').addEventListener('click', () => { const p = $('recent').value; if (p) post('/api/image/open', { path: p }); });

// ---- job fields: every change goes to the view-model, which re-plans ------------------------------------------------
document.addEventListener('input', (e) => { e.target.dataset.dirty = '1'; });
document.addEventListener('change', (e) => { delete e.target.dataset.dirty; });
document.addEventListener('focusout', (e) => { delete e.target.dataset.dirty; });
let sliderTimer = null;
let sliderValue = null;
document.querySelectorAll('[data-field]').forEach((input) => {
  const send = () => {
    const field = input.dataset.field;
    let value;
    if (input.type === 'checkbox') value = input.checked;
    else if (input.tagName === 'SELECT') value = input.value;
    else { value = Number(input.value); if (input.value.trim() === '' || !Number.isFinite(value)) { showFieldError(field, `${input.value || 'an empty field'} is not a number`); return; } }
    post('/api/job', { [field]: value });
  };
  if (input.type === 'range') {
    // The mask follows the slider while it moves, at most every 80 ms, the latest value winning.
    input.addEventListener('input', () => {
      $('threshold-value').textContent = input.value;
      sliderValue = Number(input.value);
      if (!sliderTimer) sliderTimer = setTimeout(() => { sliderTimer = null; post('/api/job', { thresholdPercent: sliderValue }); }, 80);
    });
  } else {
    input.addEventListener('change', send);
  }
});
function showFieldError(field, message) {
  const el = document.querySelector(`[data-error="${field}"]`);
  if (el) el.textContent = message;
}

// ---- machine -------------------------------------------------------------------------------------------------------
$('connect').addEventListener('click', () => post('/api/machine/connect', {
  useSimulator: $('use-simulator').checked, stagePort: $('stagePort').value || null, laserPort: $('laserPort').value || null,
}));
$('disconnect').addEventListener('click', () => post('/api/machine/disconnect'));
$('identify').addEventListener('click', () => post('/api/machine/identify'));
$('home').addEventListener('click', () => post('/api/machine/home'));
$('moves-home').addEventListener('click', () => post('/api/machine/home'));
$('refresh-ports').addEventListener('click', async () => {
  const ports = await (await fetch('/api/ports')).json();
  $('port-list').innerHTML = ports.map((p) => `<option value="${escapeHtml(p)}">`).join('');
  $('machine-error').textContent = ports.length ? '' : 'no serial ports found; type a path instead';
});

document.querySelectorAll('[name="machine-kind"]').forEach((r) => r.addEventListener('change', () => { $('stagePort').disabled = $('laserPort').disabled = $('use-simulator').checked; }));

// ---- test moves ----------------------------------------------------------------------------------------------------
let stepUm = 100;
function renderSteps(choices) {
  const labels = { 1: '1 µm', 10: '10 µm', 100: '100 µm', 1000: '1 mm', 10000: '10 mm' };
  $('steps').innerHTML = '<span class="hint">Step</span>' + choices.map((c) => `<button data-step="${c}" class="${c === stepUm ? 'active' : ''}">${labels[c] ?? c + ' µm'}</button>`).join('');
  $('steps').querySelectorAll('button').forEach((b) => b.addEventListener('click', () => { stepUm = Number(b.dataset.step); renderSteps(choices); }));
}
const jog = (direction) => post('/api/moves/jog', { direction, stepUm });
document.querySelectorAll('[data-jog]').forEach((b) => b.addEventListener('click', () => jog(b.dataset.jog)));
document.addEventListener('keydown', (e) => {
  if (currentView !== 'moves' || ['INPUT', 'SELECT', 'TEXTAREA'].includes(document.activeElement?.tagName)) return;
  const direction = { ArrowLeft: 'x-', ArrowRight: 'x+', ArrowUp: 'y-', ArrowDown: 'y+' }[e.key];
  if (direction) { e.preventDefault(); jog(direction); }
});
$('jog-stop').addEventListener('click', () => post('/api/moves/stop'));
$('goto').addEventListener('click', () => post('/api/moves/goto', { xMm: Number($('goto-x').value), yMm: Number($('goto-y').value) }));
$('goto-origin').addEventListener('click', () => post('/api/moves/origin'));
$('frame').addEventListener('click', () => post('/api/moves/frame'));
$('fire').addEventListener('click', () => post('/api/moves/fire', { pulses: Number($('fire-pulses').value) }));

// ---- run -----------------------------------------------------------------------------------------------------------
$('start').addEventListener('click', () => post('/api/run/start', { notes: $('notes').value || null, sampleId: $('sampleId').value || null }));
$('pause').addEventListener('click', () => post('/api/run/pause'));
$('resume').addEventListener('click', () => post('/api/run/resume'));
$('continue').addEventListener('click', () => post('/api/run/continue'));
$('abort').addEventListener('click', () => post('/api/run/abort'));
$('abort-top').addEventListener('click', () => post('/api/run/abort'));

// ---- log -----------------------------------------------------------------------------------------------------------
$('open-log-folder').addEventListener('click', () => post('/api/logs/open-folder'));
$('history').addEventListener('click', (e) => {
  const id = e.target.dataset?.load;
  if (id) { post('/api/logs/load', { path: id }); showView('image'); }
});

// ---- theme ---------------------------------------------------------------------------------------------------------
$('theme-toggle').addEventListener('click', () => {
  const next = document.documentElement.dataset.theme === 'dark' ? 'light' : 'dark';
  setTheme(next);
  post('/api/settings/theme', { theme: next });
});
function setTheme(theme) {
  if (document.documentElement.dataset.theme === theme) return;
  document.documentElement.dataset.theme = theme;
  $('theme-toggle').textContent = theme === 'dark' ? 'Light' : 'Dark';
  planCanvas = null;
  draw();
}

// ---- rendering the state -------------------------------------------------------------------------------------------
const fmt = (v, digits = 3) => (v === null || v === undefined) ? '—' : Number(v).toLocaleString('en-US', { maximumFractionDigits: digits });
function duration(seconds) {
  if (seconds === null || seconds === undefined) return '—';
  const s = Math.round(seconds);
  const h = Math.floor(s / 3600), m = Math.floor((s % 3600) / 60), r = s % 60;
  return h ? `${h} h ${m} min` : m ? `${m} min ${r} s` : `${r} s`;
}
function escapeHtml(text) { return String(text ?? '').replace(/[&<>"']/g, (c) => ({ '&': '&amp;', '<': '&lt;', '>': '&gt;', '"': '&quot;', "'": '&#39;' })[c]); }
function meta(el, pairs) { el.innerHTML = pairs.map(([k, v]) => `<dt>${escapeHtml(k)}</dt><dd>${escapeHtml(v)}</dd>`).join(''); }
const shownValues = new Map();
function setValue(id, value) {
  const el = $(id);
  // A field shows the server's value when that value changes; in between it keeps what the user typed (a port not yet
  // connected, notes not yet sent). A field the user is typing in is never overwritten.
  if (!el || (shownValues.has(id) && shownValues.get(id) === value)) return;
  if (document.activeElement === el && el.dataset.dirty === '1') return;
  shownValues.set(id, value);
  if (el.type === 'checkbox') el.checked = !!value;
  else if (el.type === 'number') el.value = value === null || value === undefined ? '' : Number(Number(value).toPrecision(8));
  else el.value = value ?? '';
}

let shownMaskVersion = -1;
let shownImagePath = null;
function apply(s) {
  state = s;
  setTheme(s.settings.theme);
  const job = s.job, img = s.image, m = s.machine, run = s.run;

  // image
  if (img.path !== shownImagePath) { shownImagePath = img.path; $('img-original').src = img.path ? '/api/image/original.png?' + encodeURIComponent(img.path) + '&v=' + img.maskVersion : ''; }
  if (img.maskVersion !== shownMaskVersion) { shownMaskVersion = img.maskVersion; $('img-mask').src = img.path ? '/api/image/mask.png?v=' + img.maskVersion : ''; }
  $('burn-pixels').textContent = img.burnPixels === null || img.burnPixels === undefined ? '' : `· ${fmt(img.burnPixels)} pixels to burn`;
  const i = img.info;
  meta($('image-meta'), i ? [['File', img.name], ['Format', `${i.format}, ${i.bitsPerPixel} bits per pixel${i.paletteSize ? `, ${i.paletteSize} colours` : ''}`],
    ['Pixels', `${i.width} × ${i.height}`], ['Resolution', i.dpiX ? `${fmt(i.dpiX, 1)} × ${fmt(i.dpiY, 1)} dpi` : 'not stated'],
    ['File size', `${fmt(i.fileSizeBytes / 1024, 1)} KiB`], ['Compression', i.compression], ['Transparency', i.hasAlpha ? 'yes' : 'no']] : [['File', 'none open']]);
  $('image-pair').hidden = !img.path;
  $('no-image').hidden = !!img.path;
  const recent = s.settings.recentFiles || [];
  const samples = s.samples || [];
  const option = (p) => `<option value="${escapeHtml(p)}">${escapeHtml(p.split(/[\\/]/).pop())}</option>`;
  const options = '<option value="">—</option>'
    + (recent.length ? `<optgroup label="Recent">${recent.map(option).join('')}</optgroup>` : '')
    + (samples.length ? `<optgroup label="Samples">${samples.map(option).join('')}</optgroup>` : '');
  if ($('recent').innerHTML !== options && document.activeElement !== $('recent')) $('recent').innerHTML = options;

  // job fields
  for (const f of ['thresholdPercent', 'dither', 'invert', 'aspectLocked', 'widthMm', 'heightMm', 'pitchUm', 'microstepsPerPixel', 'originXMm', 'originYMm',
    'laserFrequencyHz', 'burnSpeedMmPerS', 'travelSpeedMmPerS', 'accelerationMmPerS2', 'strategy', 'bidirectional', 'overscanMm', 'passes']) setValue(f, job[f]);
  if (document.activeElement !== $('thresholdPercent')) $('threshold-value').textContent = job.thresholdPercent;
  $('thresholdPercent').disabled = job.dither !== 'None';
  document.querySelectorAll('[data-error]').forEach((el) => { el.textContent = job.errors[el.dataset.error] ?? ''; });
  document.querySelectorAll('[data-warning]').forEach((el) => { el.textContent = job.warnings[el.dataset.warning] ?? ''; });
  document.querySelectorAll('[data-field]').forEach((el) => {
    el.classList.toggle('has-error', !!job.errors[el.dataset.field]);
    el.classList.toggle('has-warning', !!job.warnings[el.dataset.field] || (el.id.startsWith('origin') && !!job.warnings.origin));
  });

  const e = s.estimate;
  const figures = e ? [['Estimated time', duration(e.seconds)], ['Size on the stage', `${fmt(e.achievedWidthMm, 4)} × ${fmt(e.achievedHeightMm, 4)} mm`],
    ['Scale error', `${fmt(e.residualScaleError * 1e6, 1)} ppm`], ['Rows', fmt(e.rows)], ['Moves', fmt(e.moves)], ['Burn runs', fmt(e.burnRuns)],
    ['Burn length', `${fmt(e.burnLengthMm, 2)} mm`], ['Travel length', `${fmt(e.travelLengthMm, 2)} mm`], ['Fits the travel', e.fitsTravel ? 'yes' : 'NO']] : [['Estimate', 'open an image with a usable size']];
  meta($('estimate'), figures);
  meta($('size-figures'), figures.slice(1, 3).concat([['Microstep', `${fmt(m.microstepUm, 8)} µm`], ['Travel', `${fmt(m.travelXMm)} × ${fmt(m.travelYMm)} mm`]]));
  $('status-estimate').textContent = e ? `${fmt(e.achievedWidthMm, 3)} × ${fmt(e.achievedHeightMm, 3)} mm · est. ${duration(e.seconds)}` : 'no job';

  // machine
  if (shownValues.get('machine-kind') !== m.useSimulator) { shownValues.set('machine-kind', m.useSimulator); $('use-simulator').checked = m.useSimulator; $('use-ports').checked = !m.useSimulator; }
  $('stagePort').disabled = $('laserPort').disabled = $('use-simulator').checked;
  setValue('stagePort', m.stagePort); setValue('laserPort', m.laserPort);
  $('status-machine').textContent = m.connected ? `● ${m.description}` : '○ not connected';
  $('machine-error').textContent = m.error ?? '';
  ['disconnect', 'identify', 'home'].forEach((id) => { $(id).disabled = !m.connected || m.isBusy || run.active; });
  $('connect').disabled = m.isBusy || run.active;
  const axis = (mm, steps, homed) => steps === null || steps === undefined ? '—' : `${fmt(mm, 4)} mm (${fmt(steps)} microsteps)${homed === false ? ', not homed' : homed ? ', homed' : ''}`;
  meta($('machine-state'), [['Connection', m.connected ? m.description : 'not connected'], ['Profile', m.profile], ['Travel', `${fmt(m.travelXMm)} × ${fmt(m.travelYMm)} mm`],
    ['X', axis(m.xMm, m.xMicrosteps, m.xHomed)], ['Y', axis(m.yMm, m.yMicrosteps, m.yHomed)], ['Laser gate', m.gateState ?? '—'], ['Identity', m.identity ?? '—']]
    .concat(s.profileError ? [['Profile problem', s.profileError]] : []));
  meta($('moves-position'), [['X', axis(m.xMm, m.xMicrosteps, m.xHomed)], ['Y', axis(m.yMm, m.yMicrosteps, m.yHomed)], ['Laser gate', m.gateState ?? '—']]);
  $('moves-error').textContent = s.testMoves.error ?? '';
  document.querySelectorAll('#view-moves button').forEach((b) => { b.disabled = !m.connected || run.active; });
  $('jog-stop').disabled = !m.connected;
  if (!$('steps').children.length) renderSteps(s.testMoves.stepChoicesUm);

  // run
  $('status-run').textContent = run.active ? `${run.state.toLowerCase()} · ${fmt(run.percent, 1)} %` : run.state.toLowerCase();
  $('start').disabled = run.active || !s.estimate || !m.connected;
  $('pause').disabled = run.state !== 'Running';
  $('continue').disabled = !run.canContinue;
  $('continue').hidden = !run.canContinue;
  $('resume').disabled = run.state !== 'Paused';
  $('run-error').textContent = run.error ?? '';
  $('progress-bar').style.width = `${run.percent}%`;
  $('progress-text').textContent = `${fmt(run.percent, 1)} %`;
  $('progress-figures').textContent = run.active && run.phase === 'preflight' ? 'preflight: checking the machine and homing the axes before the first move…' : run.movesTotal ? `row ${fmt(run.rowsDone)} of ${fmt(run.rowsTotal)} · move ${fmt(run.movesDone)} of ${fmt(run.movesTotal)}${job.passes > 1 ? ` · pass ${run.pass} of ${job.passes}` : ''} · elapsed ${duration(run.elapsedSeconds)} · remaining ${duration(run.remainingSeconds)}${run.laserOn ? ' · laser ON' : ''}` : '';

  // log
  setValue('sampleId', s.log.sampleId); setValue('notes', s.log.notes);
  const last = s.log.lastRun;
  $('last-run').textContent = last ? last.text : 'No run yet.';
  const exportUrl = (path, format) => `/api/logs/export?format=${format}&path=${encodeURIComponent(path)}`;
  for (const [id, format] of [['export-txt', 'txt'], ['export-json', 'json']]) {
    const a = $(id);
    if (last && last.path) { a.href = exportUrl(last.path, format); a.removeAttribute('aria-disabled'); } else { a.removeAttribute('href'); a.setAttribute('aria-disabled', 'true'); }
  }
  $('log-error').textContent = s.log.error ?? '';
  $('log-notice').textContent = s.log.notice ?? '';
  const rows = s.log.history.map((r) => `<tr><td>${r.startedAt ? escapeHtml(new Date(r.startedAt).toLocaleString()) : ''}</td><td>${escapeHtml(r.sampleId ?? '')}</td><td>${escapeHtml(r.image ?? '')}</td><td>${escapeHtml(r.outcome)}${r.error ? ': ' + escapeHtml(r.error) : ''}${r.simulated ? ' (simulator)' : ''}</td><td>${duration(r.actualSeconds)}</td><td>${r.startedAt ? `<button data-load="${escapeHtml(r.path)}">Load</button> <a href="${exportUrl(r.path, 'txt')}" download>text</a> <a href="${exportUrl(r.path, 'json')}" download>JSON</a>` : ''}</td></tr>`).join('');
  if ($('history').innerHTML !== rows) $('history').innerHTML = rows || '<tr><td colspan="6" class="hint">No runs yet.</td></tr>';

  // preview
  if (job.planVersion !== plan.version && !plan.loading) loadPlan();
  updateBurned();
  scheduleDraw();
}

// ---- the preview: plan drawn once into an offscreen canvas; the burned part and the marker as cheap overlays --------
const plan = { version: -1, loading: false, data: null };
let planCanvas = null;      // the cached drawing of the plan
let burnedCanvas = null;    // what has burned so far, same mapping as planCanvas
let burnedUpTo = 0;
let burnedKey = '';
const view = { scale: 1, x: 0, y: 0, fitted: false };
const CACHE_SIDE = 2048;

async function loadPlan() {
  plan.loading = true;
  try {
    const data = await (await fetch('/api/plan')).json();
    plan.data = data;
    plan.version = data.version;
    planCanvas = null;
    burnedCanvas = null;
    burnedUpTo = 0;
    if (!view.fitted || currentView !== 'preview') view.fitted = false;
    if (currentView === 'preview' && !view.fitted) fit('job');
    scheduleDraw();
  } finally {
    plan.loading = false;
  }
}

function planBounds() {
  const d = plan.data;
  if (!d || !d.job) return null;
  let left = d.job.left, right = d.job.right, top = d.job.top, bottom = d.job.bottom;
  const m = d.moves;
  for (let i = 0; i < m.length; i += 5) {
    left = Math.min(left, m[i + 1], m[i + 3]); right = Math.max(right, m[i + 1], m[i + 3]);
    top = Math.min(top, m[i + 2], m[i + 4]); bottom = Math.max(bottom, m[i + 2], m[i + 4]);
  }
  const pad = Math.max(right - left, bottom - top) * 0.01 + 1;
  return { left: left - pad, top: top - pad, right: right + pad, bottom: bottom + pad };
}

function cssColour(name) { return getComputedStyle(document.documentElement).getPropertyValue(name).trim(); }

function buildPlanCanvas() {
  const b = planBounds();
  if (!b) return null;
  const scale = CACHE_SIDE / Math.max(b.right - b.left, b.bottom - b.top);
  const c = document.createElement('canvas');
  c.width = Math.max(1, Math.ceil((b.right - b.left) * scale));
  c.height = Math.max(1, Math.ceil((b.bottom - b.top) * scale));
  const g = c.getContext('2d');
  const d = plan.data;
  g.strokeStyle = cssColour('--border');
  g.strokeRect((d.job.left - b.left) * scale, (d.job.top - b.top) * scale, (d.job.right - d.job.left) * scale, (d.job.bottom - d.job.top) * scale);
  const rowHeight = estimateRowHeight(d) * scale;
  drawMoves(g, d.moves, 0, d.moves.length / 5, b, scale, rowHeight, false);
  return { canvas: c, bounds: b, scale, rowHeight };
}

function estimateRowHeight(d) {
  // The pitch in microsteps: the job's height over its rows; a burn line is drawn one pitch thick.
  const rows = new Set();
  for (let i = 0; i < d.moves.length; i += 5) if (d.moves[i] === 1) rows.add(d.moves[i + 2]);
  const sorted = [...rows].sort((a, b) => a - b);
  let pitch = d.job.bottom - d.job.top;
  for (let i = 1; i < sorted.length; i++) pitch = Math.min(pitch, sorted[i] - sorted[i - 1]);
  return pitch;
}

function drawMoves(g, m, from, to, b, scale, rowHeight, burnedOnly) {
  const colours = burnedOnly ? [null, cssColour('--burned'), null] : [cssColour('--travel'), cssColour('--burn'), cssColour('--overscan')];
  for (let k = 0; k < 3; k++) {
    if (!colours[k]) continue;
    g.beginPath();
    g.strokeStyle = colours[k];
    g.lineWidth = k === 1 ? Math.max(1, rowHeight * 0.9) : 1;
    g.lineCap = 'butt';
    for (let j = from; j < to; j++) {
      const i = j * 5;
      if (m[i] !== k) continue;
      g.moveTo((m[i + 1] - b.left) * scale, (m[i + 2] - b.top) * scale);
      g.lineTo((m[i + 3] - b.left) * scale, (m[i + 4] - b.top) * scale);
    }
    g.stroke();
  }
}

function updateBurned() {
  const run = state?.run;
  if (!run || !plan.data || run.runPlanVersion !== plan.version || !run.movesTotal) return;
  if (!planCanvas) planCanvas = buildPlanCanvas();
  if (!planCanvas) return;
  const key = `${plan.version}:${run.pass}:${run.state === 'Idle'}`;
  if (!burnedCanvas || key !== burnedKey || run.movesDone < burnedUpTo) {
    burnedCanvas = document.createElement('canvas');
    burnedCanvas.width = planCanvas.canvas.width; burnedCanvas.height = planCanvas.canvas.height;
    burnedUpTo = 0; burnedKey = key;
  }
  if (run.movesDone > burnedUpTo) {
    drawMoves(burnedCanvas.getContext('2d'), plan.data.moves, burnedUpTo, Math.min(run.movesDone, plan.data.moves.length / 5), planCanvas.bounds, planCanvas.scale, planCanvas.rowHeight, true);
    burnedUpTo = run.movesDone;
  }
}

function resizeCanvases() {
  const wrap = $('canvas-wrap');
  for (const c of [$('plan-canvas'), $('overlay-canvas')]) {
    const w = Math.round(wrap.clientWidth * devicePixelRatio), h = Math.round(wrap.clientHeight * devicePixelRatio);
    if (c.width !== w || c.height !== h) { c.width = w; c.height = h; }
  }
}
window.addEventListener('resize', () => { resizeCanvases(); scheduleDraw(); });

function fit(what) {
  const wrap = $('canvas-wrap');
  const w = wrap.clientWidth * devicePixelRatio, h = wrap.clientHeight * devicePixelRatio;
  if (!w || !h || !plan.data) return;
  let b = { left: 0, top: 0, right: plan.data.travelX, bottom: plan.data.travelY };
  if (what === 'job') b = planBounds() ?? b;
  const margin = 0.06;
  view.scale = Math.min(w / (b.right - b.left), h / (b.bottom - b.top)) * (1 - 2 * margin);
  view.x = (w - (b.right - b.left) * view.scale) / 2 - b.left * view.scale;
  view.y = (h - (b.bottom - b.top) * view.scale) / 2 - b.top * view.scale;
  view.fitted = true;
  scheduleDraw();
}

let drawPending = false;
function scheduleDraw() { if (!drawPending) { drawPending = true; requestAnimationFrame(() => { drawPending = false; draw(); }); } }

function draw() {
  if (currentView !== 'preview' || !plan.data) return;
  resizeCanvases();
  const c = $('plan-canvas'), g = c.getContext('2d');
  g.setTransform(1, 0, 0, 1, 0, 0);
  g.fillStyle = cssColour('--canvas-bg'); g.fillRect(0, 0, c.width, c.height);
  const d = plan.data;
  const sx = (x) => view.x + x * view.scale, sy = (y) => view.y + y * view.scale;
  // The stage's travel area, with a line every 10 mm.
  g.fillStyle = cssColour('--travel-area');
  g.fillRect(sx(0), sy(0), d.travelX * view.scale, d.travelY * view.scale);
  g.strokeStyle = cssColour('--border'); g.lineWidth = 1; g.beginPath();
  const tenMm = 10000 / d.microstepUm;
  for (let x = 0; x <= d.travelX; x += tenMm) { g.moveTo(sx(x), sy(0)); g.lineTo(sx(x), sy(d.travelY)); }
  for (let y = 0; y <= d.travelY; y += tenMm) { g.moveTo(sx(0), sy(y)); g.lineTo(sx(d.travelX), sy(y)); }
  g.stroke();
  g.fillStyle = cssColour('--muted'); g.font = `${12 * devicePixelRatio}px system-ui`;
  g.fillText('0,0', sx(0) + 4, sy(0) + 14 * devicePixelRatio);
  if (!planCanvas) planCanvas = buildPlanCanvas();
  if (planCanvas) {
    const b = planCanvas.bounds;
    g.imageSmoothingEnabled = view.scale * (b.right - b.left) < planCanvas.canvas.width;
    g.drawImage(planCanvas.canvas, sx(b.left), sy(b.top), (b.right - b.left) * view.scale, (b.bottom - b.top) * view.scale);
    if (burnedCanvas) g.drawImage(burnedCanvas, sx(b.left), sy(b.top), (b.right - b.left) * view.scale, (b.bottom - b.top) * view.scale);
  } else {
    g.fillStyle = cssColour('--muted');
    g.fillText(state?.image?.path ? 'No plan: see the messages in Size and Process.' : 'Open an image to see its plan.', 20, 30 * devicePixelRatio);
  }
  drawOverlay();
}

function drawOverlay() {
  const c = $('overlay-canvas'), g = c.getContext('2d');
  g.clearRect(0, 0, c.width, c.height);
  const m = state?.machine;
  const x = state?.run?.active ? state.run.x : m?.xMicrosteps, y = state?.run?.active ? state.run.y : m?.yMicrosteps;
  if (x === null || x === undefined || y === null || y === undefined) return;
  const px = view.x + x * view.scale, py = view.y + y * view.scale;
  g.strokeStyle = cssColour('--marker'); g.fillStyle = cssColour('--marker'); g.lineWidth = 2 * devicePixelRatio;
  g.beginPath(); g.arc(px, py, 6 * devicePixelRatio, 0, 2 * Math.PI); g.stroke();
  g.beginPath(); g.moveTo(px - 12 * devicePixelRatio, py); g.lineTo(px + 12 * devicePixelRatio, py); g.moveTo(px, py - 12 * devicePixelRatio); g.lineTo(px, py + 12 * devicePixelRatio); g.stroke();
  if (state.run.active && state.run.laserOn) { g.beginPath(); g.arc(px, py, 3 * devicePixelRatio, 0, 2 * Math.PI); g.fill(); }
}

// zoom and pan
const wrap = $('canvas-wrap');
function zoom(factor, cx, cy) {
  view.x = cx - (cx - view.x) * factor; view.y = cy - (cy - view.y) * factor; view.scale *= factor; scheduleDraw();
}
wrap.addEventListener('wheel', (e) => { e.preventDefault(); const r = wrap.getBoundingClientRect(); zoom(e.deltaY < 0 ? 1.2 : 1 / 1.2, (e.clientX - r.left) * devicePixelRatio, (e.clientY - r.top) * devicePixelRatio); }, { passive: false });
let dragging = null;
wrap.addEventListener('pointerdown', (e) => { dragging = { x: e.clientX, y: e.clientY }; wrap.setPointerCapture(e.pointerId); });
wrap.addEventListener('pointermove', (e) => { if (!dragging) return; view.x += (e.clientX - dragging.x) * devicePixelRatio; view.y += (e.clientY - dragging.y) * devicePixelRatio; dragging = { x: e.clientX, y: e.clientY }; scheduleDraw(); });
wrap.addEventListener('pointerup', () => { dragging = null; });
$('zoom-in').addEventListener('click', () => zoom(1.5, $('plan-canvas').width / 2, $('plan-canvas').height / 2));
$('zoom-out').addEventListener('click', () => zoom(1 / 1.5, $('plan-canvas').width / 2, $('plan-canvas').height / 2));
$('zoom-job').addEventListener('click', () => fit('job'));
$('zoom-travel').addEventListener('click', () => fit('travel'));

// ---- start ---------------------------------------------------------------------------------------------------------
(async () => {
  apply(await (await fetch('/api/state')).json());
  connectEvents();
  const wanted = location.hash.replace('#', '');
  if (document.getElementById('view-' + wanted)) showView(wanted);
})();
