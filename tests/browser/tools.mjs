// Shared by the viewer's Node checks: where the test-only npm packages are (installed by the
// CMake target sinew_browser_test_tools into build/tests/browser/node_modules, see
// tests/browser/package.json) and the exit code CTest counts as skipped.
import { createRequire } from 'node:module';
import fs from 'node:fs';
import path from 'node:path';

export const SKIP = 77;

export function skip(reason) {
  console.log(`SKIP: ${reason}`);
  process.exit(SKIP);
}

// require() rooted at the tools folder (SINEW_BROWSER_TOOLS), or a skip when it is not there.
export function toolsRequire() {
  const dir = process.env.SINEW_BROWSER_TOOLS;
  if (!dir || !fs.existsSync(path.join(dir, 'node_modules'))) {
    skip(`test tools not installed in '${dir}' (run scripts/test, or cmake --build build --target sinew_browser_test_tools)`);
  }
  return createRequire(path.join(path.resolve(dir), 'package.json'));
}

// Debian's chromium (package chromium), or the browser named by SINEW_CHROMIUM.
export function chromiumPath() {
  const exe = process.env.SINEW_CHROMIUM || '/usr/bin/chromium';
  if (!fs.existsSync(exe)) skip(`no browser at ${exe} (Debian package chromium)`);
  return exe;
}

export function requireFile(file, what) {
  if (!fs.existsSync(file)) skip(`${what} ${file} was not made (an earlier step skipped or failed)`);
}
