// Validates a SARIF file against the OASIS SARIF 2.1.0 JSON schema (draft-04).
// usage: node validate-sarif.js SCHEMA SARIF  -> exit 0 when valid, 1 with the errors otherwise
'use strict';
const fs = require('fs');
const Ajv = require('ajv-draft-04');
const addFormats = require('ajv-formats');
const [schemaPath, sarifPath] = process.argv.slice(2);
// unicodeRegExp off: the rtm.5 schema (the copy npm ships) has a pattern only non-unicode regexps accept.
const ajv = new Ajv({ allErrors: true, strict: false, unicodeRegExp: false });
addFormats(ajv);
const validate = ajv.compile(JSON.parse(fs.readFileSync(schemaPath, 'utf8')));
if (validate(JSON.parse(fs.readFileSync(sarifPath, 'utf8')))) {
  console.log('valid');
} else {
  console.log(JSON.stringify(validate.errors, null, 2));
  process.exit(1);
}
