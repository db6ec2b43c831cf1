// Runs the Khronos glTF-Validator (npm package gltf-validator) on assets and prints, per asset and
// in the order given, its report summary as one JSON object on one line: {"asset": PATH,
// "errors": N, "warnings": N, "infos": N, "hints": N, "messages": [{"code", "severity",
// "pointer", "message"}...]} (severity 0 = error ... 3 = hint).
//
//   node validate_gltf.js VALIDATOR_DIR ASSET...
//
// VALIDATOR_DIR is the npm prefix the package was installed into. Several assets in one call
// save a Node start each (the validator suite has hundreds). External resources (buffers,
// images) are resolved only inside each asset's own folder: a uri that escapes it is reported as
// an IO error, never opened. Exit status: 0 when the validator ran on every asset (whatever it
// found), 1 when it could not run. A file the validator cannot even read as glTF (an empty file, a
// GLB header of another format) is reported as one error of code VALIDATOR_UNREADABLE.
'use strict';
const fs = require('fs');
const path = require('path');

if (process.argv.length < 4) {
    console.error('usage: node validate_gltf.js VALIDATOR_DIR ASSET...');
    process.exit(1);
}
const validator = require(path.join(path.resolve(process.argv[2]), 'node_modules', 'gltf-validator'));

function readInside(folder, uri) {
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

async function validate(given) {
    const asset = path.resolve(given);
    const folder = fs.realpathSync(path.dirname(asset));
    const report = await validator.validateBytes(new Uint8Array(fs.readFileSync(asset)), {
        uri: path.basename(asset),
        maxIssues: 0,
        writeTimestamp: false,
        externalResourceFunction: (uri) => readInside(folder, uri),
    });
    const issues = report.issues;
    return {
        asset: given,
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
}

(async () => {
    for (const asset of process.argv.slice(3)) {
        let out;
        try {
            out = await validate(asset);
        } catch (error) {
            if (!fs.existsSync(asset)) {
                console.error('validator could not run on ' + asset + ': ' + error);
                process.exit(1);
            }
            const message = String(error);
            out = {asset: asset, errors: 1, warnings: 0, infos: 0, hints: 0,
                   messages: [{code: 'VALIDATOR_UNREADABLE', severity: 0, pointer: '', message}]};
        }
        console.log(JSON.stringify(out));
    }
})();
