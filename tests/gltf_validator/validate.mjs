// Runs the Khronos glTF validator (npm gltf-validator) on each file given and
// prints one line per file: "<errors> <warnings> <path>", then every error
// message and every unused object (UNUSED_OBJECT, an information the
// validator gives for accessors, views... nothing references). Exit 0 when no file has an error, 1 otherwise, 77 when the npm
// package is not installed (the calling test then skips).
import fs from 'node:fs';
import path from 'node:path';
import { createRequire } from 'node:module';

const require = createRequire(import.meta.url);
let validator;
try {
  validator = require('gltf-validator');
} catch (e) {
  console.log('gltf-validator is not installed: run npm ci in tests/gltf_validator');
  process.exit(77);
}

let failed = false;
for (const file of process.argv.slice(2)) {
  const bytes = new Uint8Array(fs.readFileSync(file));
  const report = await validator.validateBytes(bytes, {
    uri: file,
    maxIssues: 100,
    externalResourceFunction: (uri) =>
      new Promise((resolve, reject) => {
        fs.readFile(path.resolve(path.dirname(file), decodeURIComponent(uri)), (err, data) =>
          err ? reject(err.toString()) : resolve(new Uint8Array(data)));
      }),
  });
  const s = report.issues;
  console.log(`${s.numErrors} ${s.numWarnings} ${file}`);
  for (const m of s.messages)
    if (m.severity === 0 || m.code === 'UNUSED_OBJECT')
      console.log(`  ${m.severity === 0 ? 'error' : 'info'} ${m.code} ${m.pointer || ''}: ${m.message}`);
  if (s.numErrors > 0) failed = true;
}
process.exit(failed ? 1 : 0);
