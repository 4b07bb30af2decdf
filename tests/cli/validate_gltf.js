// node validate_gltf.js NODE_MODULES FILE.glb: runs the Khronos glTF validator (npm gltf-validator)
// on a file and prints one JSON line: {"errors": N, "warnings": N, "messages": [...first errors]}.
// Exit status 2 when the validator cannot run.
const fs = require('fs');
const path = require('path');
let validator;
try {
  validator = require(path.resolve(process.argv[2], 'gltf-validator'));
} catch (e) {
  console.error('cannot load gltf-validator from ' + process.argv[2] + ': ' + e.message);
  process.exit(2);
}
const bytes = new Uint8Array(fs.readFileSync(process.argv[3]));
validator.validateBytes(bytes, {maxIssues: 0}).then((report) => {
  const issues = report.issues;
  const shown = issues.messages.filter((m) => m.severity <= 1).slice(0, 20)
    .map((m) => (m.severity === 0 ? 'error ' : 'warning ') + m.code + ' ' + (m.pointer || '') + ': ' + m.message);
  console.log(JSON.stringify({errors: issues.numErrors, warnings: issues.numWarnings, infos: issues.numInfos, messages: shown}));
}).catch((e) => {
  console.error('validator failed: ' + e);
  process.exit(2);
});
