// Opens a written viewer page in headless Chromium (playwright-core over Debian's chromium)
// with no network: every request other than the page itself fails the check.
import path from 'node:path';
import { pathToFileURL } from 'node:url';
import { toolsRequire, chromiumPath } from './tools.mjs';

export async function openViewer(html, { frame = 0, field = '', width = 640, height = 480, controls = true } = {}) {
  const { chromium } = toolsRequire()('playwright-core');
  const browser = await chromium.launch({
    executablePath: chromiumPath(),
    // WebGL on the CPU (SwiftShader), so the test needs no GPU and renders the same everywhere.
    args: ['--use-angle=swiftshader', '--enable-unsafe-swiftshader', '--ignore-gpu-blocklist', '--no-sandbox'],
  });
  const page = await browser.newPage({ viewport: { width, height }, deviceScaleFactor: 1 });
  const url = pathToFileURL(path.resolve(html));
  const foreign = [];
  const errors = [];
  page.on('request', (r) => { if (!r.url().startsWith(url.href)) foreign.push(r.url()); });
  page.on('pageerror', (e) => errors.push(String(e)));
  page.on('console', (m) => { if (m.type() === 'error') errors.push(m.text()); });
  url.search = new URLSearchParams({ frame: String(frame), field, play: '0', controls: controls ? '1' : '0' }).toString();
  await page.goto(url.href);
  await page.waitForFunction(() => document.body.dataset.ready === '1' || document.body.dataset.error, null, { timeout: 30000 });
  const error = await page.evaluate(() => document.body.dataset.error);
  if (error) errors.push(error);
  // Two animation frames, so the last state change is on screen.
  await page.evaluate(() => new Promise((r) => requestAnimationFrame(() => requestAnimationFrame(r))));
  return { browser, page, foreign, errors };
}
