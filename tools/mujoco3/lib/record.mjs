// The run record (docs/run-record.md): JSON Lines, a header, one line per physics step, an end
// line. State only: what happened, never a verdict.
import { closeSync, openSync, writeSync } from "node:fs";

export class RecordWriter {
  constructor(file) {
    this.file = file;
    this.fd = openSync(file, "w");
    this.chunks = [];
    this.size = 0;
  }
  line(object) {
    const text = JSON.stringify(object) + "\n";
    this.chunks.push(text);
    this.size += text.length;
    if (this.size > 1 << 20) this.flush();
  }
  flush() {
    if (this.chunks.length) writeSync(this.fd, this.chunks.join(""));
    this.chunks = [];
    this.size = 0;
  }
  close() {
    this.flush();
    closeSync(this.fd);
  }
}
