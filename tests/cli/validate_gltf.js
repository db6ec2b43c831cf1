// Runs the Khronos glTF-Validator (npm package gltf-validator) on one asset and prints its report
// summary as one JSON object: {"errors": N, "warnings": N, "infos": N, "hints": N, "messages":
// [{"code", "severity", "pointer", "message"}...]} (severity 0 = error ... 3 = hint).
//
//   node validate_gltf.js VALIDATOR_DIR ASSET
//
// VALIDATOR_DIR is the npm prefix the package was installed into. External resources (buffers,
// images) are resolved only inside the asset's own folder: a uri that escapes it is reported as
// an IO error, never opened. Exit status: 0 when the validator ran (whatever it found), 1 when it
// could not run.
'use strict';
const fs = require('fs');
const path = require('path');

if (process.argv.length !== 4) {
    console.error('usage: node validate_gltf.js VALIDATOR_DIR ASSET');
    process.exit(1);
}
const validator = require(path.join(path.resolve(process.argv[2]), 'node_modules', 'gltf-validator'));
const asset = path.resolve(process.argv[3]);
const folder = fs.realpathSync(path.dirname(asset));

function readInside(uri) {
    return new Promise((resolve, reject) => {
        let decoded;
        try {
            decoded = decodeURIComponent(uri);
        } catch (e) {
            reject('bad uri ' + uri);
            return;
        }
        const target = path.resolve(folder, decoded);
        let real;
        try {
            real = fs.realpathSync(target);
        } catch (e) {
            reject('not found: ' + uri);
            return;
        }
        if (path.relative(folder, real).startsWith('..') || path.isAbsolute(path.relative(folder, real))) {
            reject('refused: ' + uri + ' is outside the asset folder');
            return;
        }
        fs.readFile(real, (err, data) => (err ? reject(err.toString()) : resolve(new Uint8Array(data))));
    });
}

validator
    .validateBytes(new Uint8Array(fs.readFileSync(asset)), {
        uri: path.basename(asset),
        maxIssues: 0,
        writeTimestamp: false,
        externalResourceFunction: readInside,
    })
    .then((report) => {
        const issues = report.issues;
        const out = {
            errors: issues.numErrors,
            warnings: issues.numWarnings,
            infos: issues.numInfos,
            hints: issues.numHints,
            messages: issues.messages.map((m) => ({
                code: m.code,
                severity: m.severity,
                pointer: m.pointer,
                message: m.message,
            })),
        };
        console.log(JSON.stringify(out));
    })
    .catch((error) => {
        console.error('validator could not run: ' + error);
        process.exit(1);
    });
