// node validate_glb.mjs FILE.glb: the Khronos glTF validator's verdict; exit 1 on any error.
import fs from 'node:fs';
import { toolsRequire, requireFile } from './tools.mjs';

const file = process.argv[2];
const require = toolsRequire();
requireFile(file, 'GLB');
const validator = require('gltf-validator');
const report = await validator.validateBytes(new Uint8Array(fs.readFileSync(file)), { maxIssues: 100 });
const { numErrors, numWarnings, numInfos, messages } = report.issues;
// Errors and warnings in full; infos (the field arrays are listed only in extras, so the
// validator calls them unused) and hints are counted.
for (const m of messages.filter((x) => x.severity <= 1)) console.log(`${['error', 'warning', 'info', 'hint'][m.severity]} ${m.code} ${m.pointer || ''}: ${m.message}`);
const info = report.info || {};
console.log(`${file}: ${numErrors} errors, ${numWarnings} warnings, ${numInfos} infos; ` +
  `${info.drawCallCount} draw calls, ${info.totalVertexCount} vertices, ${info.animationCount} animations, morph targets: ${info.hasMorphTargets}`);
if (numErrors > 0) process.exit(1);
if (!info.hasMorphTargets || info.animationCount !== 1) {
  console.log('expected morph targets and one animation');
  process.exit(1);
}
