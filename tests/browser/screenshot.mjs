// node screenshot.mjs VIEWER.html OUT.png [--frame N] [--field NAME] [--size WxH] [--controls]
// A picture of a written viewer (the docs' images, scripts/render_docs_images.sh): headless
// Chromium, fixed camera, the controls bar only with --controls. Frame -1 (the default) is the last frame.
import fs from 'node:fs';
import { openViewer } from './viewer_page.mjs';

const [html, out, ...rest] = process.argv.slice(2);
const option = (name, fallback) => (rest.includes(name) ? rest[rest.indexOf(name) + 1] : fallback);
const [width, height] = option('--size', '640x400').split('x').map(Number);
let frame = Number(option('--frame', '-1'));
const { browser, page, errors } = await openViewer(html, { frame: 0, field: option('--field', 'von_mises'), width, height, controls: rest.includes('--controls') });
try {
  if (errors.length) throw new Error(errors.join(' | '));
  const frames = await page.evaluate(() => window.sinewViewer.frames.length);
  if (frame < 0) frame = frames + frame;
  await page.evaluate((f) => window.sinewViewer.setFrame(f), frame);
  fs.writeFileSync(out, await page.screenshot());
  console.log(`${out}: frame ${frame + 1}/${frames}`);
} finally {
  await browser.close();
}
