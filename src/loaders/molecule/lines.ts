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
  /** The next '\r' in the buffer at or after `at` (Infinity: none; below `at`: to be looked for). */
  private cr = -1;
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
      // indexOf for '\n' per line, '\r' looked for again only once passed: most files have none, and
      // a regular expression per line took twice as long (a file of blank lines is all line ends).
      if (this.cr < at) {
        const cr = buffer.indexOf('\r', at);
        this.cr = cr < 0 ? Infinity : cr;
      }
      const lf = buffer.indexOf('\n', at);
      const end = this.cr < (lf < 0 ? buffer.length : lf) ? this.cr : lf;
      if ((end >= 0 ? end : buffer.length) - at > MAX_LINE_CHARACTERS) throw this.tooLong(this.index + 2);
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
      this.refill();
    }
  }

  /**
   * Skips lines of nothing but ASCII white space up to the next line with anything else (or the
   * end), and says how many: a character at a time, where `next` costs a call and a string a line
   * (512 MiB of line breaks took 22 s of `next`). A line of other white space is left to `next`.
   */
  skipBlankLines(): number {
    let count = 0;
    for (;;) {
      const { buffer } = this;
      const more = this.offset < this.input.length;
      let i = this.at;
      let lineStart = i;
      for (; i < buffer.length; ) {
        const c = buffer.charCodeAt(i);
        if (c === 10 || c === 13) {
          // A '\r' ending the slice may be half of a '\r\n': read more first.
          if (c === 13 && more && i === buffer.length - 1) break;
          if (i - lineStart > MAX_LINE_CHARACTERS) throw this.tooLong(this.index + count + 2);
          i += c === 13 && buffer.charCodeAt(i + 1) === 10 ? 2 : 1;
          count++;
          lineStart = i;
        } else if (c === 32 || c === 9 || c === 11 || c === 12) i++;
        else {
          i = -1;
          break;
        }
      }
      this.at = lineStart;
      const content = i < 0;
      // A blank line still open at the end of the slice is carried into the next: bound it as next() does.
      if (!content && buffer.length - lineStart > MAX_LINE_CHARACTERS) throw this.tooLong(this.index + count + 2);
      if (content || !more) {
        this.index += count;
        return count;
      }
      // A blank line still open at the end of the slice: refill and look on.
      this.refill();
    }
  }

  /** The refusal of line `line` (1-based). */
  private tooLong(line: number): LanternError {
    return new LanternError(`${this.source} line ${line}: a line longer than ${MAX_LINE_CHARACTERS.toLocaleString('en-US')} characters`, 'molfile lines are at most 80 characters: this is not a molecule file, or it is damaged');
  }

  private refill(): void {
    const bytes = this.input as Uint8Array;
    const to = Math.min(bytes.length, this.offset + SLICE_BYTES);
    this.buffer = this.buffer.slice(this.at) + this.decoder.decode(bytes.subarray(this.offset, to), { stream: to < bytes.length });
    this.offset = to;
    this.at = 0;
    this.cr = -1;
  }
}
