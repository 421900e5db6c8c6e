// The stage canvas: the whole travel in mm with rulers, grid, the job (mask, plan, burned part), the laser, zoom, pan,
// dragging the job and right-click "move the laser here". Everything else on the page is Blazor; this is the only script.
const RULER = 22;
const KINDS = { travel: 0, burn: 1, overscan: 2 };

export function create(host, dotnet) {
  const canvas = host.querySelector('canvas');
  const cursor = host.querySelector('[data-cursor]');
  const menu = host.querySelector('[data-menu]');
  const ctx = canvas.getContext('2d');
  // Fluent UI's theme marks the body dark (the theme switch's choice, or the system's) and says when that changes.
  const isDark = () => document.body.getAttribute('data-theme') === 'dark';
  const s = {
    travel: { w: 60, h: 60 }, job: null, layers: [], draggable: false, laser: null, laserOn: false,
    moves: new Float32Array(0), paths: null, burned: null, burnedUpTo: 0, movesDone: 0,
    mask: null, maskUrl: null, scale: 1, ox: 0, oy: 0, fitted: false, userView: false, drag: null, raf: 0,
  };
  const css = (name) => getComputedStyle(host).getPropertyValue(name).trim() || '#888';
  const toMm = (px, py) => ({ x: (px - s.ox) / s.scale, y: (py - s.oy) / s.scale });
  const invalidate = () => { if (!s.raf) s.raf = requestAnimationFrame(draw); };

  function resize() {
    const r = host.getBoundingClientRect(), d = window.devicePixelRatio || 1;
    canvas.width = Math.max(1, Math.round(r.width * d));
    canvas.height = Math.max(1, Math.round(r.height * d));
    canvas.style.width = r.width + 'px';
    canvas.style.height = r.height + 'px';
    // The whole travel stays fitted to a resized window until the user zooms or pans.
    if (!s.fitted || !s.userView) fit(); else invalidate();
  }

  // From a quarter of the whole travel's fit up to 1 µm a screen pixel: deeper, the rulers have no mark left to draw and
  // the plan's lines (a microstep is 0.1 µm at best) show nothing more.
  const MAX_SCALE = 1000;
  function clampScale(scale) {
    const r = host.getBoundingClientRect();
    const least = Math.max(0.1, Math.min((r.width - RULER) / s.travel.w, (r.height - RULER) / s.travel.h) / 4);
    return Math.min(MAX_SCALE, Math.max(least, scale));
  }

  // The job's box is in view, at least in part.
  function jobInView(job) {
    const r = host.getBoundingClientRect(), a = toMm(RULER, RULER), b = toMm(r.width, r.height);
    return job.x < b.x && job.x + job.w > a.x && job.y < b.y && job.y + job.h > a.y;
  }

  function fit() {
    const r = host.getBoundingClientRect(), m = 12;
    const w = r.width - RULER - 2 * m, h = r.height - RULER - 2 * m;
    if (w <= 0 || h <= 0) return;
    s.scale = Math.min(w / s.travel.w, h / s.travel.h);
    s.ox = RULER + m + (w - s.travel.w * s.scale) / 2;
    s.oy = RULER + m + (h - s.travel.h * s.scale) / 2;
    s.fitted = true; s.userView = false;
    invalidate();
  }

  function buildPaths() {
    const p = [new Path2D(), new Path2D(), new Path2D()], m = s.moves;
    for (let i = 0; i < m.length; i += 5) { const k = p[m[i]] || p[0]; k.moveTo(m[i + 1], m[i + 2]); k.lineTo(m[i + 3], m[i + 4]); }
    s.paths = p;
    s.burned = new Path2D(); s.burnedUpTo = 0;
    extendBurned();
  }

  function extendBurned() {
    const m = s.moves, end = Math.min(s.movesDone, m.length / 5);
    if (end < s.burnedUpTo) { s.burned = new Path2D(); s.burnedUpTo = 0; }
    for (let i = s.burnedUpTo; i < end; i++) {
      const j = i * 5;
      if (m[j] === KINDS.burn) { s.burned.moveTo(m[j + 1], m[j + 2]); s.burned.lineTo(m[j + 3], m[j + 4]); }
    }
    s.burnedUpTo = end;
  }

  function gridStep(minPx) {
    for (const base of [0.01, 0.1, 1, 10, 100]) for (const f of [1, 2, 5]) if (base * f * s.scale >= minPx) return base * f;
    return 100;
  }

  function draw() {
    s.raf = 0;
    const d = window.devicePixelRatio || 1, W = canvas.width / d, H = canvas.height / d;
    ctx.setTransform(d, 0, 0, d, 0, 0);
    ctx.fillStyle = css('--canvas-bg'); ctx.fillRect(0, 0, W, H);
    const tx = s.travel.w, ty = s.travel.h;
    const x0 = s.ox, y0 = s.oy, x1 = s.ox + tx * s.scale, y1 = s.oy + ty * s.scale;
    ctx.fillStyle = css('--travel-area'); ctx.fillRect(x0, y0, x1 - x0, y1 - y0);
    // Grid: minor and major lines clipped to the travel.
    const step = gridStep(12), major = gridStep(60);
    ctx.save(); ctx.beginPath(); ctx.rect(x0, y0, x1 - x0, y1 - y0); ctx.clip();
    for (const [st, col] of [[step, css('--grid-minor')], [major, css('--grid-major')]]) {
      ctx.beginPath(); ctx.strokeStyle = col; ctx.lineWidth = 1;
      const from = Math.max(0, Math.floor(-s.ox / s.scale / st) * st), fromY = Math.max(0, Math.floor(-s.oy / s.scale / st) * st);
      for (let v = from; v <= tx + 1e-9 && s.ox + v * s.scale <= W; v += st) { const px = Math.round(s.ox + v * s.scale) + 0.5; ctx.moveTo(px, y0); ctx.lineTo(px, y1); }
      for (let v = fromY; v <= ty + 1e-9 && s.oy + v * s.scale <= H; v += st) { const py = Math.round(s.oy + v * s.scale) + 0.5; ctx.moveTo(x0, py); ctx.lineTo(x1, py); }
      ctx.stroke();
    }
    ctx.restore();
    ctx.strokeStyle = css('--border-strong'); ctx.lineWidth = 1; ctx.strokeRect(x0 + 0.5, y0 + 0.5, x1 - x0, y1 - y0);

    // The camera's stitched map of the sample, under the job, in mm coordinates.
    if (s.map && s.map.img.complete && s.map.img.naturalWidth > 0) {
      ctx.save(); ctx.setTransform(d * s.scale, 0, 0, d * s.scale, d * s.ox, d * s.oy);
      ctx.drawImage(s.map.img, s.map.x, s.map.y, s.map.w, s.map.h);
      ctx.restore();
    }

    // The job, in mm coordinates.
    const job = s.drag && s.drag.kind === 'job' ? { ...s.job, x: s.drag.x, y: s.drag.y } : s.job;
    ctx.save(); ctx.setTransform(d * s.scale, 0, 0, d * s.scale, d * s.ox, d * s.oy);
    if (job) {
      const dx = job.x - s.job.x, dy = job.y - s.job.y;
      if (s.mask && s.mask.complete && s.mask.naturalWidth > 0) {
        // Burned pixels dark on a light stage, light on a dark one, like the plan's burns.
        ctx.imageSmoothingEnabled = false; ctx.globalAlpha = 0.35; ctx.filter = isDark() ? 'invert(1)' : 'none';
        ctx.drawImage(s.mask, job.x, job.y, job.w, job.h); ctx.globalAlpha = 1; ctx.filter = 'none';
      }
      if (s.paths) {
        ctx.translate(dx, dy);
        const px = 1 / s.scale;
        ctx.lineWidth = px; ctx.strokeStyle = css('--travel'); ctx.stroke(s.paths[KINDS.travel]);
        ctx.strokeStyle = css('--overscan'); ctx.stroke(s.paths[KINDS.overscan]);
        ctx.lineWidth = Math.max(px, job.pitch || px); ctx.strokeStyle = css('--burn'); ctx.stroke(s.paths[KINDS.burn]);
        if (s.burnedUpTo > 0) { ctx.strokeStyle = css('--burned'); ctx.stroke(s.burned); }
        ctx.translate(-dx, -dy);
      }
      ctx.lineWidth = 1.5 / s.scale; ctx.setLineDash(s.selected ? [] : [6 / s.scale, 4 / s.scale]);
      ctx.strokeStyle = job.fits ? css('--accent') : css('--danger');
      if (s.layers.length === 0) ctx.strokeRect(job.x, job.y, job.w, job.h);
      ctx.setLineDash([]);
      if (s.selected && s.layers.length === 0) {
        // Selected: a solid outline with a handle at each corner, as a drawing program shows it.
        const h = 6 / s.scale; ctx.fillStyle = css('--accent');
        for (const [cx, cy] of [[job.x, job.y], [job.x + job.w, job.y], [job.x, job.y + job.h], [job.x + job.w, job.y + job.h]]) ctx.fillRect(cx - h / 2, cy - h / 2, h, h);
      }
    }
    // A job of layers: each layer's box, numbered and named in burn order.
    ctx.font = `${11 / s.scale}px system-ui, sans-serif`; ctx.textBaseline = 'bottom';
    const labels = new Map();
    for (const l of s.layers) {
      ctx.lineWidth = 1.2 / s.scale; ctx.setLineDash([4 / s.scale, 3 / s.scale]);
      ctx.strokeStyle = l.fits ? css('--accent') : css('--danger');
      ctx.strokeRect(l.x, l.y, l.w, l.h); ctx.setLineDash([]);
      // Layers of one drawing share its box: one label names them all.
      const key = `${l.x},${l.y}`, label = labels.get(key);
      labels.set(key, label ? { ...label, name: `${label.name} · ${l.name}`, fits: label.fits && l.fits } : { x: l.x, y: l.y, name: l.name, fits: l.fits });
    }
    // Each label as large as fits before the next box's label to its right and the label row above (a sweep's 1 mm
    // cells leave little room); one that would be smaller than 7 px is left out until the view is zoomed in.
    const placed = [...labels.values()];
    const rows = [...new Set(placed.map((l) => l.y))].sort((a, b) => a - b);
    const rowStepMm = rows.length > 1 ? Math.min(...rows.slice(1).map((y, i) => y - rows[i])) : Infinity;
    const drawn = [];
    for (const l of placed) {
      const next = Math.min(...placed.filter((o) => o.y === l.y && o.x > l.x).map((o) => o.x));
      ctx.font = `${11 / s.scale}px system-ui, sans-serif`;
      const widthMm = ctx.measureText(l.name).width, roomMm = next - l.x - 3 / s.scale;
      const px = Math.min(11, 11 * roomMm / widthMm, rowStepMm * s.scale - 3);
      if (!(px >= 7)) continue;
      ctx.font = `${px / s.scale}px system-ui, sans-serif`;
      ctx.fillStyle = l.fits ? css('--accent') : css('--danger');
      ctx.fillText(l.name, l.x, l.y - 2 / s.scale);
      const w = ctx.measureText(l.name).width;
      drawn.push([s.ox + l.x * s.scale, s.oy + (l.y - 2 / s.scale) * s.scale - px, s.ox + (l.x + w) * s.scale, s.oy + (l.y - 2 / s.scale) * s.scale]);
    }
    ctx.restore();
    // The boxes' labels as drawn (px: left, top, right, bottom), for tests that check none overlaps another.
    host.dataset.boxLabels = JSON.stringify(drawn.map((b) => b.map((v) => Math.round(v * 10) / 10)));

    // The laser: a cross, filled while it fires.
    if (s.laser) {
      const lx = s.ox + s.laser.x * s.scale, ly = s.oy + s.laser.y * s.scale;
      ctx.strokeStyle = css('--marker'); ctx.fillStyle = css('--marker'); ctx.lineWidth = 2;
      ctx.beginPath(); ctx.moveTo(lx - 10, ly); ctx.lineTo(lx + 10, ly); ctx.moveTo(lx, ly - 10); ctx.lineTo(lx, ly + 10); ctx.stroke();
      ctx.beginPath(); ctx.arc(lx, ly, 5, 0, 2 * Math.PI); s.laserOn ? ctx.fill() : ctx.stroke();
      // The cross as drawn (px) with the view it was drawn in and the instant it stands for (s on the machine's clock, in a run),
      // for tests that compare it with the simulator's stage at that instant.
      host.dataset.laserDrawn = `${lx},${ly},${s.scale},${s.ox},${s.oy},${s.laser.at ?? ''}`;
    } else {
      delete host.dataset.laserDrawn;
    }
    drawRulers(W, H, major, step);
    // The view's scale and offset (px per mm, px), for tests that drag the job where it is drawn.
    host.dataset.view = `${s.scale},${s.ox},${s.oy}`;
  }

  function drawRulers(W, H, major, minor) {
    ctx.fillStyle = css('--ruler-bg'); ctx.fillRect(0, 0, W, RULER); ctx.fillRect(0, 0, RULER, H);
    ctx.strokeStyle = css('--ruler-text'); ctx.fillStyle = css('--ruler-text'); ctx.lineWidth = 1;
    ctx.font = '10px system-ui, sans-serif'; ctx.textBaseline = 'top';
    ctx.beginPath();
    const label = (v) => (Math.round(v * 100) / 100).toString();
    // A label goes after its tick, or before it where it would run off the canvas (the travel's last mark, "60").
    const rulerLabels = [];
    for (let v = Math.max(0, Math.ceil(((RULER - s.ox) / s.scale) / minor) * minor); v <= s.travel.w + 1e-9; v += minor) {
      const px = Math.round(s.ox + v * s.scale) + 0.5; if (px > W) break;
      const isMajor = Math.abs(v / major - Math.round(v / major)) < 1e-6;
      ctx.moveTo(px, RULER); ctx.lineTo(px, isMajor ? 4 : RULER - 6);
      if (isMajor) {
        const t = label(v), w = ctx.measureText(t).width, x = px + 2 + w <= W ? px + 2 : px - 2 - w;
        ctx.fillText(t, x, 2); rulerLabels.push(['x', t, x, 2, x + w, 12]);
      }
    }
    for (let v = Math.max(0, Math.ceil(((RULER - s.oy) / s.scale) / minor) * minor); v <= s.travel.h + 1e-9; v += minor) {
      const py = Math.round(s.oy + v * s.scale) + 0.5; if (py > H) break;
      const isMajor = Math.abs(v / major - Math.round(v / major)) < 1e-6;
      ctx.moveTo(RULER, py); ctx.lineTo(isMajor ? 4 : RULER - 6, py);
      if (isMajor) {
        const t = label(v), w = ctx.measureText(t).width, y = py + 2 + w <= H ? py + 2 : py - 2 - w;
        ctx.save(); ctx.translate(2, y); ctx.rotate(Math.PI / 2); ctx.fillText(t, 0, -10); ctx.restore();
        rulerLabels.push(['y', t, 2, y, 12, y + w]);
      }
    }
    ctx.stroke();
    // The rulers' labels as drawn (axis, text, px box), for tests that check none is cut off.
    host.dataset.rulerLabels = JSON.stringify(rulerLabels.map((l) => l.map((v) => typeof v === 'number' ? Math.round(v * 10) / 10 : v)));
    ctx.fillStyle = css('--ruler-bg'); ctx.fillRect(0, 0, RULER, RULER);
    ctx.fillStyle = css('--ruler-text'); ctx.fillText('mm', 2, 6);
  }

  const local = (e) => { const r = canvas.getBoundingClientRect(); return { px: e.clientX - r.left, py: e.clientY - r.top }; };
  const inJob = (mm) => s.job && s.draggable && mm.x >= s.job.x && mm.x <= s.job.x + s.job.w && mm.y >= s.job.y && mm.y <= s.job.y + s.job.h;
  const snap = (v) => Math.round(v * 100) / 100;
  const fmt = (v) => v.toFixed(2);

  canvas.addEventListener('wheel', (e) => {
    e.preventDefault();
    const { px, py } = local(e), mm = toMm(px, py), k = e.deltaY < 0 ? 1.2 : 1 / 1.2;
    s.scale = clampScale(s.scale * k); s.userView = true;
    s.ox = px - mm.x * s.scale; s.oy = py - mm.y * s.scale;
    invalidate();
  }, { passive: false });

  canvas.addEventListener('pointerdown', (e) => {
    menu.hidden = true;
    if (e.button !== 0 && e.button !== 1) return;
    const { px, py } = local(e), mm = toMm(px, py);
    canvas.setPointerCapture(e.pointerId);
    s.drag = e.button === 0 && inJob(mm)
      ? { kind: 'job', sx: mm.x, sy: mm.y, x: s.job.x, y: s.job.y }
      : { kind: 'pan', px, py, ox: s.ox, oy: s.oy };
    // A click on the job selects it (the arrow keys then move it); a click beside it leaves it.
    if (e.button === 0) select(s.drag.kind === 'job');
    canvas.style.cursor = s.drag.kind === 'job' ? 'move' : 'grabbing';
  });

  canvas.addEventListener('pointermove', (e) => {
    const { px, py } = local(e), mm = toMm(px, py);
    const on = mm.x >= 0 && mm.y >= 0 && mm.x <= s.travel.w && mm.y <= s.travel.h;
    cursor.textContent = on ? `X ${fmt(mm.x)}  Y ${fmt(mm.y)} mm` : '';
    if (!s.drag) { canvas.style.cursor = inJob(mm) ? 'move' : 'crosshair'; return; }
    if (s.drag.kind === 'pan') { s.ox = s.drag.ox + px - s.drag.px; s.oy = s.drag.oy + py - s.drag.py; s.userView = true; }
    else {
      s.drag.x = snap(s.job.x + mm.x - s.drag.sx); s.drag.y = snap(s.job.y + mm.y - s.drag.sy);
      cursor.textContent = `origin X ${fmt(s.drag.x)}  Y ${fmt(s.drag.y)} mm`;
    }
    invalidate();
  });

  // The job placed at (x, y) mm: drawn there at once, put back when the app refuses the place.
  const place = async (x, y) => {
    const previous = s.job;
    s.job = { ...s.job, x, y };
    invalidate();
    const accepted = await dotnet.invokeMethodAsync('OnJobDropped', x, y);
    if (!accepted) { s.job = previous; invalidate(); }
  };
  const select = (on) => {
    s.selected = !!(on && s.job && s.draggable);
    host.dataset.selected = s.selected ? 'true' : 'false';
    invalidate();
  };
  const endDrag = async () => {
    const d = s.drag; s.drag = null; canvas.style.cursor = 'crosshair';
    if (d && d.kind === 'job' && (d.x !== s.job.x || d.y !== s.job.y)) await place(d.x, d.y);
    else invalidate();
  };
  canvas.addEventListener('pointerleave', () => { if (!s.drag) cursor.textContent = ''; });
  canvas.addEventListener('pointerup', endDrag);
  canvas.addEventListener('pointercancel', endDrag);

  canvas.addEventListener('contextmenu', (e) => {
    e.preventDefault();
    const { px, py } = local(e), mm = toMm(px, py);
    if (mm.x < 0 || mm.y < 0 || mm.x > s.travel.w || mm.y > s.travel.h) { menu.hidden = true; return; }
    const x = snap(mm.x), y = snap(mm.y);
    menu.querySelector('[data-where]').textContent = `${fmt(x)}, ${fmt(y)} mm`;
    menu.style.left = px + 'px'; menu.style.top = py + 'px'; menu.hidden = false;
    menu.dataset.x = x; menu.dataset.y = y;
  });
  menu.querySelector('button').addEventListener('click', () => {
    menu.hidden = true;
    dotnet.invokeMethodAsync('OnMoveLaserHere', Number(menu.dataset.x), Number(menu.dataset.y));
  });

  // Keyboard jog anywhere on the page, except while typing in a field.
  const keys = { ArrowLeft: 'x-', ArrowRight: 'x+', ArrowUp: 'y-', ArrowDown: 'y+' };
  const onKey = (e) => {
    const t = e.target, typing = t && (t.isContentEditable || /^(INPUT|TEXTAREA|SELECT)$/.test(t.tagName) || t.closest?.('input,textarea,select,fluent-text-input'));
    // F1 (help) and Esc (stop a test move, close the help) act everywhere, even while typing; Esc never touches a run.
    if (e.key === 'F1' && !e.ctrlKey && !e.altKey && !e.metaKey) {
      e.preventDefault();
      dotnet.invokeMethodAsync('OnShortcutKey', 'help');
      return;
    }
    if (e.key === 'Escape' && !e.ctrlKey && !e.altKey && !e.metaKey) {
      select(false);
      dotnet.invokeMethodAsync('OnShortcutKey', 'escape');
      return;
    }
    const key = e.key.toLowerCase(), ctrl = (e.ctrlKey || e.metaKey) && !e.altKey;
    // Ctrl+O and Ctrl+S are the app's, never the browser's (open a file, save the page), even in a field.
    if (ctrl && (key === 'o' || key === 's')) {
      e.preventDefault();
      if (typing) return;
      // Clicked here, within the key press, because a file chooser opens only on the user's own gesture.
      if (key === 'o') { const file = document.getElementById('file'); if (file && !file.disabled) file.click(); }
      else dotnet.invokeMethodAsync('OnShortcutKey', 'save');
      return;
    }
    // Ctrl+Z and Ctrl+Y (or Ctrl+Shift+Z) undo and redo the job's changes; in a field they stay the field's own.
    if (!typing && ctrl && (key === 'z' || key === 'y')) {
      e.preventDefault();
      dotnet.invokeMethodAsync('OnShortcutKey', key === 'y' || e.shiftKey ? 'redo' : 'undo');
      return;
    }
    if (typing || e.altKey || e.metaKey || !keys[e.key]) return;
    e.preventDefault();
    // Shift+arrows jog the stage (the real machine); the arrows alone move the selected job, 0.1 mm (Ctrl: 1 mm), as in
    // a drawing program: never the stage unasked.
    if (e.shiftKey && !e.ctrlKey) { dotnet.invokeMethodAsync('OnJogKey', keys[e.key]); return; }
    if (!s.selected || !s.job || !s.draggable) { dotnet.invokeMethodAsync('OnShortcutKey', 'arrow-unselected'); return; }
    const step = e.ctrlKey ? 1 : 0.1, d = keys[e.key];
    const x = snap(s.job.x + (d === 'x+' ? step : d === 'x-' ? -step : 0)), y = snap(s.job.y + (d === 'y+' ? step : d === 'y-' ? -step : 0));
    place(x, y);
  };
  document.addEventListener('keydown', onKey);
  document.body.addEventListener('themeChanged', invalidate);
  const observer = new ResizeObserver(resize);
  observer.observe(host);
  resize();
  // When the workspace became usable (the circuit is up and the stage drawn), for the page-load figures.
  performance.mark('laserengrave-ready');

  return {
    setTravel(w, h) { s.travel = { w, h }; s.fitted = false; resize(); },
    setJob(job, draggable) {
      if (!job || !draggable) select(false);
      // A job newly opened or resized off the part of the stage in view: the whole travel again, so the stage is never
      // shown empty with the job somewhere outside it.
      const changed = !s.job || !job || job.w !== s.job.w || job.h !== s.job.h || job.x !== s.job.x || job.y !== s.job.y;
      s.job = job; s.draggable = draggable;
      if (job && changed && s.userView && !jobInView(job)) fit(); else invalidate();
    },
    setLayers(layers) { s.layers = layers || []; invalidate(); },
    setMap(url, x, y, w, h) {
      if (!url) { s.map = null; invalidate(); return; }
      const img = new Image();
      img.onload = () => invalidate();
      img.src = url;
      s.map = { img, x, y, w, h };
    },
    setMask(url) {
      if (url === s.maskUrl) return;
      s.maskUrl = url;
      if (!url) { s.mask = null; invalidate(); return; }
      // Fetched with the token (an image element could only send cookies, and the page keeps none), drawn once decoded.
      window.laserEngrave.fetch(url).then((r) => (r.ok ? r.blob() : null)).then((blob) => {
        if (!blob || s.maskUrl !== url) return;
        const img = new Image();
        img.onload = () => { URL.revokeObjectURL(img.src); invalidate(); };
        img.src = URL.createObjectURL(blob);
        s.mask = img;
      });
    },
    async setPlan(stream) {
      const buffer = stream ? await stream.arrayBuffer() : new ArrayBuffer(0);
      s.moves = new Float32Array(buffer); buildPaths(); invalidate();
      return s.moves.length / 5;
    },
    setProgress(movesDone) { s.movesDone = movesDone; extendBurned(); invalidate(); },
    setLaser(x, y, on, at) { s.laser = x === null ? null : { x, y, at }; s.laserOn = on; invalidate(); },
    fit,
    zoom(k) { s.userView = true; const r = host.getBoundingClientRect(), cx = r.width / 2, cy = r.height / 2, mm = toMm(cx, cy); s.scale = clampScale(s.scale * k); s.ox = cx - mm.x * s.scale; s.oy = cy - mm.y * s.scale; invalidate(); },
    dispose() { document.removeEventListener('keydown', onKey); document.body.removeEventListener('themeChanged', invalidate); observer.disconnect(); },
  };
}
