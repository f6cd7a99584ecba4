// Usage: node validate.js FILE.glb -> prints the validator's JSON report; exit 0 when
// it has no errors and no warnings, 1 otherwise, 2 when it could not run.
const fs = require('fs');
const path = require('path');
const validator = require('gltf-validator');
const file = process.argv[2];
if (!file) { console.error('usage: validate.js FILE'); process.exit(2); }
const bytes = new Uint8Array(fs.readFileSync(file));
validator.validateBytes(bytes, {
  uri: path.basename(file),
  externalResourceFunction: (uri) => Promise.reject(new Error('external resources are not used')),
}).then((report) => {
  // exitCode, not exit(): a report past the pipe's buffer must be flushed first.
  console.log(JSON.stringify(report, null, 1));
  const i = report.issues;
  process.exitCode = i.numErrors === 0 && i.numWarnings === 0 ? 0 : 1;
}).catch((e) => { console.error(e.message || String(e)); process.exit(2); });
