// Usage: node validate.mjs FILE.glb — prints the Khronos validator's summary as JSON and exits
// 1 if it reports any error, 2 if the file cannot be read.
import { readFile } from 'node:fs/promises';
import validator from 'gltf-validator';

const path = process.argv[2];
let bytes;
try {
  bytes = new Uint8Array(await readFile(path));
} catch (e) {
  console.error(`${path}: cannot read (${e.message})`);
  process.exit(2);
}
const report = await validator.validateBytes(bytes, { maxIssues: 100 });
const summary = {
  file: path,
  errors: report.issues.numErrors,
  warnings: report.issues.numWarnings,
  infos: report.issues.numInfos,
  hints: report.issues.numHints,
  messages: report.issues.messages.filter((m) => m.severity <= 1).map((m) => `${m.code} ${m.pointer ?? ''} ${m.message}`),
};
console.log(JSON.stringify(summary, null, 2));
process.exit(summary.errors > 0 ? 1 : 0);
