// node validate_gltf.js FILE.glb|FILE.gltf — the Khronos glTF validator (npm gltf-validator) on one file; prints its
// report's issues as JSON and exits 0 when it has no error, 1 when it has, 2 when the validator could not run.
// NODE_PATH must reach the gltf-validator module (scripts/test_tools.sh installs it under build/test-tools).
"use strict";
const fs = require("fs");
const path = require("path");
const validator = require("gltf-validator");

const file = process.argv[2];
const bytes = new Uint8Array(fs.readFileSync(file));
const folder = path.dirname(file);
validator
  .validateBytes(bytes, {
    uri: path.basename(file),
    maxIssues: 200,
    externalResourceFunction: (uri) =>
      new Promise((resolve, reject) => {
        try {
          resolve(new Uint8Array(fs.readFileSync(path.join(folder, decodeURIComponent(uri)))));
        } catch (e) {
          reject(e.toString());
        }
      }),
  })
  .then((report) => {
    console.log(JSON.stringify({ validatorVersion: report.validatorVersion, issues: report.issues }));
    process.exit(report.issues.numErrors > 0 ? 1 : 0);
  })
  .catch((e) => {
    console.error("gltf-validator failed: " + e);
    process.exit(2);
  });
