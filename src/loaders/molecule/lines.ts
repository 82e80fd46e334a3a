/**
 * The lines of a molfile or SD file one at a time, any line ending (\r\n, \r, \n), decoded from the
 * bytes in slices. Splitting the whole text up front held every line of a file at once (a 94 MB file of
 * 2 million atoms took 976 MB before a single atom was read), and a text over V8's largest string
 * (2^29 − 24 characters) could not be decoded at all; here only the current slice and the current line
 * are held, so a file costs what its molecules keep.
 */
import { LanternError } from '../../errors.ts';

/**
 * CTfile lines are at most 80 characters (V3000 continues longer ones with '-'); SD data items are
 * longer, but no real one comes near this. A longer line is refused rather than gathered: a file with
 * no line break would otherwise be collected into one string as large as the file.
 */
export const MAX_LINE_CHARACTERS = 1 << 20;

/** Bytes decoded at a time. */
const SLICE_BYTES = 1 << 22;

export class LineReader {
  private buffer = '';
  private at = 0;
  private offset = 0;
  private readonly decoder = new TextDecoder();
  private readonly breaks = /[\r\n]/g;
  /** 0-based index of the line `next` returned last (−1 before the first). */
  index = -1;

  constructor(
    private readonly input: Uint8Array | string,
    private readonly source: string,
  ) {
    if (typeof input === 'string') {
      this.buffer = input;
      this.offset = input.length;
    }
  }

  /** The next line without its ending, or undefined at the end (a final line ending starts no line). */
  next(): string | undefined {
    for (;;) {
      const { buffer, at } = this;
      const more = this.offset < this.input.length;
      this.breaks.lastIndex = at;
      const end = this.breaks.exec(buffer)?.index ?? -1;
      if ((end >= 0 ? end : buffer.length) - at > MAX_LINE_CHARACTERS) {
        throw new LanternError(`${this.source} line ${this.index + 2}: a line longer than ${MAX_LINE_CHARACTERS.toLocaleString('en-US')} characters`, 'molfile lines are at most 80 characters: this is not a molecule file, or it is damaged');
      }
      // A '\r' at the end of the slice may be the first half of '\r\n': decide once more is read.
      if (end >= 0 && !(more && end === buffer.length - 1 && buffer[end] === '\r')) {
        this.at = end + (buffer[end] === '\r' && buffer[end + 1] === '\n' ? 2 : 1);
        this.index++;
        return buffer.slice(at, end);
      }
      if (!more) {
        if (at >= buffer.length) return undefined;
        this.at = buffer.length;
        this.index++;
        return buffer.slice(at);
      }
      const bytes = this.input as Uint8Array;
      const to = Math.min(bytes.length, this.offset + SLICE_BYTES);
      this.buffer = buffer.slice(at) + this.decoder.decode(bytes.subarray(this.offset, to), { stream: to < bytes.length });
      this.offset = to;
      this.at = 0;
    }
  }
}
