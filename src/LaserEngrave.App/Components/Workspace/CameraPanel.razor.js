// The camera panel's page side: a live camera through getUserMedia (any camera the operating system offers: UVC, USB
// microscopes, grabbers with a DirectShow/Media Foundation or V4L2 driver), its sharpness, and clicks as camera pixels.
const state = new WeakMap();

export function attach(host, dotnet, width, height, live, frameWidth, frameHeight) {
  detach(host);
  const s = { stream: null, timer: 0, dotnet, frameWidth, frameHeight, sending: null, lastSent: 0 };
  state.set(host, s);
  host.addEventListener('click', s.onClick = (e) => {
    const r = host.getBoundingClientRect();
    dotnet.invokeMethodAsync('OnCameraClick', (e.clientX - r.left) * width / r.width, (e.clientY - r.top) * height / r.height);
  });
  if (!live) return;
  const video = host.querySelector('video');
  if (!navigator.mediaDevices || !navigator.mediaDevices.getUserMedia) {
    dotnet.invokeMethodAsync('OnLiveCamera', null, 'this browser offers no camera to the page (it needs 127.0.0.1 or localhost)');
    return;
  }
  navigator.mediaDevices.getUserMedia({ video: { width: { ideal: width }, height: { ideal: height } }, audio: false })
    .then((stream) => {
      s.stream = stream;
      video.srcObject = stream;
      const track = stream.getVideoTracks()[0];
      video.addEventListener('playing', () => {
        dotnet.invokeMethodAsync('OnLiveCamera', `${track.label} (${video.videoWidth} x ${video.videoHeight})`, null);
        s.timer = setInterval(() => dotnet.invokeMethodAsync('OnLiveSharpness', sharpness(video)), 500);
      }, { once: true });
    })
    .catch((err) => dotnet.invokeMethodAsync('OnLiveCamera', null, `the camera could not be opened: ${err.name}: ${err.message}`));
}

export function detach(host) {
  const s = state.get(host);
  if (!s) return;
  clearInterval(s.timer);
  if (s.onClick) host.removeEventListener('click', s.onClick);
  if (s.stream) s.stream.getTracks().forEach((t) => t.stop());
  state.delete(host);
}

// The server asked for a frame (calibration, the focus sweep, a map, a mark): the camera's next frames after the request
// (one it took before may still be queued), shrunk to the size the server expects, grey, streamed to the server. Never
// closer than 120 ms to the last (the server refuses a flood); a request during a send gets a frame of its own after it.
export function sendFrame(host) {
  const s = state.get(host);
  if (!s || !s.stream) return;
  if (s.sending) { s.again = true; return; }
  const video = host.querySelector('video');
  s.sending = (async () => {
    await nextVideoFrame(video);
    await nextVideoFrame(video);
    const wait = s.lastSent + 120 - performance.now();
    if (wait > 0) await new Promise((r) => setTimeout(r, wait));
    const w = s.frameWidth, h = s.frameHeight;
    const canvas = s.frameCanvas || (s.frameCanvas = document.createElement('canvas'));
    canvas.width = w; canvas.height = h;
    const ctx = canvas.getContext('2d', { willReadFrequently: true });
    ctx.drawImage(video, 0, 0, w, h);
    const rgba = ctx.getImageData(0, 0, w, h).data;
    const grey = new Uint8Array(w * h);
    for (let i = 0; i < grey.length; i++) grey[i] = Math.round(0.299 * rgba[4 * i] + 0.587 * rgba[4 * i + 1] + 0.114 * rgba[4 * i + 2]);
    s.lastSent = performance.now();
    await s.dotnet.invokeMethodAsync('OnLiveFrame', w, h, DotNet.createJSStreamReference(grey));
  })().catch(() => {}).finally(() => {
    s.sending = null;
    if (s.again) { s.again = false; sendFrame(host); }
  });
}

function nextVideoFrame(video) {
  return new Promise((resolve) => {
    if (video.requestVideoFrameCallback) {
      video.requestVideoFrameCallback(() => resolve());
      setTimeout(resolve, 500);
    } else {
      setTimeout(resolve, 50);
    }
  });
}

// The figure of Core/Camera/FocusMeasure.cs on the frame's grey: mean squared neighbour difference over the mean squared, x 1000.
function sharpness(video) {
  const w = video.videoWidth, h = video.videoHeight;
  if (!w || !h) return 0;
  const canvas = sharpness.canvas || (sharpness.canvas = document.createElement('canvas'));
  canvas.width = w; canvas.height = h;
  const ctx = canvas.getContext('2d', { willReadFrequently: true });
  ctx.drawImage(video, 0, 0, w, h);
  const rgba = ctx.getImageData(0, 0, w, h).data;
  const grey = new Float64Array(w * h);
  for (let i = 0; i < grey.length; i++) grey[i] = 0.299 * rgba[4 * i] + 0.587 * rgba[4 * i + 1] + 0.114 * rgba[4 * i + 2];
  let sum = 0, energy = 0, n = 0;
  for (let y = 0; y < h - 1; y++) {
    for (let x = 0; x < w - 1; x++) {
      const here = grey[y * w + x], gx = grey[y * w + x + 1] - here, gy = grey[(y + 1) * w + x] - here;
      energy += gx * gx + gy * gy; sum += here; n++;
    }
  }
  const mean = sum / n;
  return n && mean > 0 ? 1000 * energy / n / (mean * mean) : 0;
}
