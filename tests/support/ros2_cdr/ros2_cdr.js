// ROS 2 CDR, encoded and decoded by Foxglove's implementation
// (@foxglove/rosmsg2-serialization) with ROS 2 Humble's message definitions
// (@foxglove/rosmsg-msgs-common): what lineloc's tests check its own wire
// format against.
//
//   node ros2_cdr.js decode <package/Type> <file of CDR bytes>   -> JSON on stdout
//   node ros2_cdr.js encode <package/Type> <JSON file> <file written>
//
// Numeric arrays come out as JSON arrays; byte arrays as base64 under "base64".
"use strict";
const fs = require("fs");
const { MessageReader, MessageWriter } = require("@foxglove/rosmsg2-serialization");
const { ros2humble } = require("@foxglove/rosmsg-msgs-common");

function definitionsOf(type) {
  const found = new Map();
  const visit = (name) => {
    const definition = ros2humble[name];
    if (definition === undefined) {
      throw new Error(`no ROS 2 Humble message ${name}`);
    }
    if (found.has(name)) {
      return;
    }
    found.set(name, definition);
    for (const field of definition.definitions) {
      if (field.isComplex) {
        visit(field.type);
      }
    }
  };
  visit(type);
  return [...found.values()];
}

function toJson(value) {
  if (value instanceof Uint8Array) {
    return { base64: Buffer.from(value).toString("base64") };
  }
  if (ArrayBuffer.isView(value)) {
    return Array.from(value);
  }
  if (Array.isArray(value)) {
    return value.map(toJson);
  }
  if (value !== null && typeof value === "object") {
    return Object.fromEntries(Object.entries(value).map(([k, v]) => [k, toJson(v)]));
  }
  return value;
}

function fromJson(value) {
  if (Array.isArray(value)) {
    return value.map(fromJson);
  }
  if (value !== null && typeof value === "object") {
    if (Object.keys(value).length === 1 && typeof value.base64 === "string") {
      return new Uint8Array(Buffer.from(value.base64, "base64"));
    }
    return Object.fromEntries(Object.entries(value).map(([k, v]) => [k, fromJson(v)]));
  }
  return value;
}

const [command, type, input, output] = process.argv.slice(2);
const definitions = definitionsOf(type);
if (command === "decode") {
  const reader = new MessageReader(definitions);
  const message = reader.readMessage(fs.readFileSync(input));
  process.stdout.write(JSON.stringify(toJson(message)) + "\n");
} else if (command === "encode") {
  const writer = new MessageWriter(definitions);
  fs.writeFileSync(output, writer.writeMessage(fromJson(JSON.parse(fs.readFileSync(input)))));
} else {
  throw new Error("usage: ros2_cdr.js decode|encode <package/Type> <in> [out]");
}
