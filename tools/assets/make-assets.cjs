// Regenerates the starter images in assets/: a QR code (1-bit BMP), a text banner and a line drawing (1-bit PNGs).
// Deterministic: running it again gives the same bytes.
// The QR matrix comes from the npm package "qrcode"; the files are written byte by byte here.
'use strict';
const fs = require('fs');
const path = require('path');
const zlib = require('zlib');
const QRCode = require('qrcode');

const out = path.join(__dirname, '..', '..', 'assets');

// A 1-bit image: rows top to bottom, true = black (burn).
function makeImage(width, height) {
  return { width, height, px: Array.from({ length: height }, () => new Array(width).fill(false)) };
}

// 1-bit BMP, bottom-up rows padded to 4 bytes, palette index 0 = black, 1 = white (as Paint writes it).
function writeBmp(file, img) {
  const stride = Math.ceil(img.width / 32) * 4;
  const offset = 14 + 40 + 8;
  const buf = Buffer.alloc(offset + stride * img.height);
  buf.write('BM', 0, 'ascii');
  buf.writeUInt32LE(buf.length, 2);
  buf.writeUInt32LE(offset, 10);
  buf.writeUInt32LE(40, 14);
  buf.writeInt32LE(img.width, 18);
  buf.writeInt32LE(img.height, 22);
  buf.writeUInt16LE(1, 26);
  buf.writeUInt16LE(1, 28);
  buf.writeUInt32LE(0, 30);
  buf.writeUInt32LE(stride * img.height, 34);
  buf.writeInt32LE(3780, 38); // 96 dpi
  buf.writeInt32LE(3780, 42);
  buf.writeUInt32LE(2, 46);
  buf.writeUInt32LE(2, 50);
  Buffer.from([0, 0, 0, 0, 255, 255, 255, 0]).copy(buf, 54);
  for (let y = 0; y < img.height; y++) {
    const row = offset + (img.height - 1 - y) * stride;
    for (let x = 0; x < img.width; x++) {
      if (!img.px[y][x]) buf[row + (x >> 3)] |= 0x80 >> (x & 7);
    }
  }
  fs.writeFileSync(file, buf);
}

function chunk(type, data) {
  const len = Buffer.alloc(4);
  len.writeUInt32BE(data.length);
  const body = Buffer.concat([Buffer.from(type, 'ascii'), data]);
  const crc = Buffer.alloc(4);
  crc.writeUInt32BE(zlib.crc32(body) >>> 0);
  return Buffer.concat([len, body, crc]);
}

// 1-bit greyscale PNG: bit 1 = white, so black pixels are 0 bits.
function writePng(file, img) {
  const stride = Math.ceil(img.width / 8);
  const raw = Buffer.alloc((stride + 1) * img.height);
  for (let y = 0; y < img.height; y++) {
    for (let x = 0; x < img.width; x++) {
      if (!img.px[y][x]) raw[y * (stride + 1) + 1 + (x >> 3)] |= 0x80 >> (x & 7);
    }
  }
  const ihdr = Buffer.alloc(13);
  ihdr.writeUInt32BE(img.width, 0);
  ihdr.writeUInt32BE(img.height, 4);
  ihdr[8] = 1;
  const phys = Buffer.alloc(9);
  phys.writeUInt32BE(3780, 0);
  phys.writeUInt32BE(3780, 4);
  phys[8] = 1;
  fs.writeFileSync(file, Buffer.concat([
    Buffer.from([0x89, 0x50, 0x4e, 0x47, 0x0d, 0x0a, 0x1a, 0x0a]),
    chunk('IHDR', ihdr), chunk('pHYs', phys), chunk('IDAT', zlib.deflateSync(raw, { level: 9 })), chunk('IEND', Buffer.alloc(0)),
  ]));
}

// QR code: one pixel per module, with the standard four-module quiet zone.
function qrCode(text) {
  const qr = QRCode.create(text, { errorCorrectionLevel: 'M' });
  const n = qr.modules.size;
  const quiet = 4;
  const img = makeImage(n + 2 * quiet, n + 2 * quiet);
  for (let y = 0; y < n; y++) {
    for (let x = 0; x < n; x++) img.px[y + quiet][x + quiet] = qr.modules.get(y, x) === 1;
  }
  return { img, version: qr.version, size: n };
}

// A 5 x 9 pixel font (rows top to bottom, '#' = ink); rows 7 and 8 hold descenders.
const font = {
  L: ['#    ', '#    ', '#    ', '#    ', '#    ', '#    ', '#####', '     ', '     '],
  E: ['#####', '#    ', '#    ', '#### ', '#    ', '#    ', '#####', '     ', '     '],
  a: ['     ', '     ', ' ### ', '    #', ' ####', '#   #', ' ####', '     ', '     '],
  s: ['     ', '     ', ' ####', '#    ', ' ### ', '    #', '#### ', '     ', '     '],
  e: ['     ', '     ', ' ### ', '#   #', '#####', '#    ', ' ### ', '     ', '     '],
  r: ['     ', '     ', '# ## ', '##  #', '#    ', '#    ', '#    ', '     ', '     '],
  n: ['     ', '     ', '# ## ', '##  #', '#   #', '#   #', '#   #', '     ', '     '],
  g: ['     ', '     ', ' ####', '#   #', '#   #', ' ####', '    #', '    #', ' ### '],
  v: ['     ', '     ', '#   #', '#   #', '#   #', ' # # ', '  #  ', '     ', '     '],
};

function banner(text, scale, margin) {
  const advance = 6;
  const img = makeImage(text.length * advance * scale - scale + 2 * margin, 9 * scale + 2 * margin);
  [...text].forEach((ch, i) => {
    const glyph = font[ch];
    if (!glyph) throw new Error(`no glyph for '${ch}'`);
    for (let gy = 0; gy < 9; gy++) {
      for (let gx = 0; gx < 5; gx++) {
        if (glyph[gy][gx] !== '#') continue;
        for (let dy = 0; dy < scale; dy++) {
          for (let dx = 0; dx < scale; dx++) img.px[margin + gy * scale + dy][margin + (i * advance + gx) * scale + dx] = true;
        }
      }
    }
  });
  return img;
}

// Two concentric circles, a four-pointed compass star and an Archimedean spiral at its centre, drawn with a round pen.
function lineDrawing(size) {
  const img = makeImage(size, size);
  const c = size / 2;
  const pen = 1.6;
  const dot = (x, y) => {
    for (let py = Math.floor(y - pen); py <= Math.ceil(y + pen); py++) {
      for (let px = Math.floor(x - pen); px <= Math.ceil(x + pen); px++) {
        if (px >= 0 && py >= 0 && px < size && py < size && (px + 0.5 - x) ** 2 + (py + 0.5 - y) ** 2 <= pen * pen) img.px[py][px] = true;
      }
    }
  };
  const line = (x0, y0, x1, y1) => {
    const steps = Math.ceil(Math.hypot(x1 - x0, y1 - y0) * 4);
    for (let i = 0; i <= steps; i++) dot(x0 + (x1 - x0) * i / steps, y0 + (y1 - y0) * i / steps);
  };
  for (const r of [0.47, 0.42]) {
    const R = r * size;
    const steps = Math.ceil(2 * Math.PI * R * 4);
    for (let i = 0; i < steps; i++) dot(c + R * Math.cos(2 * Math.PI * i / steps), c + R * Math.sin(2 * Math.PI * i / steps));
  }
  const star = [];
  for (let k = 0; k < 8; k++) {
    const a = -Math.PI / 2 + k * Math.PI / 4;
    const r = (k % 2 === 0 ? 0.40 : 0.16) * size;
    star.push([c + r * Math.cos(a), c + r * Math.sin(a)]);
  }
  for (let k = 0; k < 8; k++) line(...star[k], ...star[(k + 1) % 8]);
  const turns = 3;
  const maxR = 0.11 * size;
  for (let t = 0; t <= 1; t += 1 / 4000) {
    const a = 2 * Math.PI * turns * t;
    dot(c + maxR * t * Math.cos(a), c + maxR * t * Math.sin(a));
  }
  return img;
}

const qr = qrCode('LaserEngrave: 2D laser micromachining on a Zaber X-Y stage');
writeBmp(path.join(out, 'qr-code.bmp'), qr.img);
writePng(path.join(out, 'text-banner.png'), banner('LaserEngrave', 4, 12));
writePng(path.join(out, 'line-drawing.png'), lineDrawing(320));
console.log(`qr-code.bmp: version ${qr.version}, ${qr.size} modules, ${qr.img.width} x ${qr.img.height} px`);
