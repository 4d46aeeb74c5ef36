// Validate glTF files with the Khronos glTF validator (npm gltf-validator);
// print, per file, its text and the validator's counts and messages as JSON.
const validator = require('gltf-validator');
const fs = require('fs');

async function main() {
    const out = [];
    for (const file of process.argv.slice(2)) {
        const text = fs.readFileSync(file, 'utf8');
        const report = await validator.validateString(text, { uri: file });
        out.push({ file, text, validator: report.validatorVersion, issues: report.issues });
    }
    console.log(JSON.stringify(out, null, 1));
}

main().catch((e) => { console.error(e); process.exit(1); });
