// node screenshot_test.mjs VIEWER.html REFERENCE.png OUT_DIR [--update]
// Loads a written viewer offline in headless Chromium, checks the controls (play/pause, frame
// slider, field menu), takes a screenshot at a fixed frame, field and camera, and compares it
// with the committed reference (pixelmatch; a small share of differing pixels is tolerated,
// for rasterisation differences between Chromium versions). --update rewrites the reference.
import fs from 'node:fs';
import path from 'node:path';
import { toolsRequire, requireFile } from './tools.mjs';
import { openViewer } from './viewer_page.mjs';

const [html, reference, outDir] = process.argv.slice(2, 5);
const update = process.argv.includes('--update');
const require = toolsRequire();
requireFile(html, 'viewer page');
const { PNG } = require('pngjs');
const pixelmatch = require('pixelmatch');
const FRAME = 2, FIELD = 'von_mises', MAX_DIFFERENT = 0.005;

let failures = 0;
function check(ok, what) {
  console.log(`${ok ? 'ok  ' : 'FAIL'} ${what}`);
  if (!ok) failures += 1;
}

fs.mkdirSync(outDir, { recursive: true });
const { browser, page, foreign, errors } = await openViewer(html, { frame: FRAME, field: FIELD });
try {
  const shot = await page.screenshot();
  const actualPath = path.join(outDir, 'screenshot.png');
  fs.writeFileSync(actualPath, shot);

  // ---- the controls
  const state = await page.evaluate(() => ({ frames: window.sinewViewer.frames.length, fields: window.sinewViewer.fields }));
  check(state.frames > FRAME, `the page has ${state.frames} frames`);
  check(state.fields.includes('J') && state.fields.includes('von_mises'), `fields ${state.fields.join(', ')}`);
  check((await page.textContent('span')).startsWith(`frame ${FRAME} `), `label shows frame ${FRAME}: "${await page.textContent('span')}"`);
  check((await page.textContent('#play')) === 'Play', 'paused on load (play=0)');
  await page.click('#play');
  check((await page.textContent('#play')) === 'Pause', 'play button starts playback');
  await page.click('#play');
  await page.$eval('#frame', (s) => { s.value = '1'; s.dispatchEvent(new Event('input')); });
  check((await page.textContent('span')).startsWith('frame 1 '), 'slider moves to frame 1');
  await page.selectOption('#field', 'J');
  check(await page.evaluate(() => document.querySelector('#field').value) === 'J', 'field menu selects J');
  await page.selectOption('#field', '');
  check(await page.evaluate(() => !document.querySelector('#legend').checkVisibility()), 'no colour hides the colour bar');
  check(foreign.length === 0, `no network requests${foreign.length ? ': ' + foreign.join(' ') : ''}`);
  check(errors.length === 0, `no page errors${errors.length ? ': ' + errors.join(' | ') : ''}`);

  // ---- the picture
  const actual = PNG.sync.read(shot);
  const background = [0xee, 0xf0, 0xf3];
  let drawn = 0;
  for (let i = 0; i < actual.data.length; i += 4)
    if (Math.abs(actual.data[i] - background[0]) + Math.abs(actual.data[i + 1] - background[1]) + Math.abs(actual.data[i + 2] - background[2]) > 24) drawn += 1;
  check(drawn > 0.05 * actual.width * actual.height, `the body covers ${(100 * drawn / (actual.width * actual.height)).toFixed(1)}% of the picture`);
  if (update) {
    fs.copyFileSync(actualPath, reference);
    console.log(`reference written: ${reference}`);
  } else {
    requireFile(reference, 'reference image');
    const expected = PNG.sync.read(fs.readFileSync(reference));
    if (expected.width !== actual.width || expected.height !== actual.height) {
      check(false, `size ${actual.width}x${actual.height} matches the reference ${expected.width}x${expected.height}`);
    } else {
      const diff = new PNG({ width: actual.width, height: actual.height });
      const different = pixelmatch(expected.data, actual.data, diff.data, actual.width, actual.height, { threshold: 0.1 });
      fs.writeFileSync(path.join(outDir, 'diff.png'), PNG.sync.write(diff));
      const share = different / (actual.width * actual.height);
      check(share <= MAX_DIFFERENT, `${different} pixels (${(100 * share).toFixed(2)}%) differ from ${reference} ` +
        `(at most ${100 * MAX_DIFFERENT}%; picture and diff in ${outDir})`);
    }
  }
} finally {
  await browser.close();
}
process.exit(failures ? 1 : 0);
