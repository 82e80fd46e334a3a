/**
 * Text from files (lump, map and texture names, paths, glTF strings) reaches the terminal in
 * messages. A name holding ESC, BEL or a C1 control could set the terminal's title, clear the screen
 * or forge a line, so everything the CLI writes passes through `escapeControls` first; and the
 * process leaves only after stdout and stderr have drained, so that a slow reader of a pipe gets
 * every byte.
 */

// C0 controls but tab and newline, DEL and C1 controls; tab and newline are kept only where a caller
// writes several lines (a one-line message escapes its newlines too).
const CONTROLS = /[\u0000-\u0008\u000B-\u001F\u007F-\u009F]/g;
const CONTROLS_AND_NEWLINES = /[\u0000-\u001F\u007F-\u009F]/g;

/**
 * `text` with every control character written as `\u00XX`: readable, impossible for a terminal to
 * act on, and a valid escape inside a JSON string, so JSON output stays JSON.
 */
export function escapeControls(text: string, { keepLines = false }: { keepLines?: boolean } = {}): string {
  return text.replace(keepLines ? CONTROLS : CONTROLS_AND_NEWLINES, (c) => `\\u${c.charCodeAt(0).toString(16).toUpperCase().padStart(4, '0')}`);
}

/**
 * Resolves once everything written to `stream` so far has been handed to the system. A write
 * callback runs after the writes before it; an error (the reader went away) ends the wait too.
 */
export function drained(stream: NodeJS.WritableStream & { writableLength?: number; destroyed?: boolean }): Promise<void> {
  if (stream.destroyed) return Promise.resolve();
  return new Promise((resolve) => {
    stream.once('error', () => resolve());
    stream.write('', () => resolve());
  });
}

/**
 * Ends the process once stdout and stderr have drained. process.exit() alone drops what is still
 * queued for a pipe (the reader gets the first 64 KiB); Dawn's native threads keep the process alive
 * otherwise, so leaving is explicit.
 */
export async function exitWhenDrained(code: number): Promise<never> {
  await Promise.all([drained(process.stdout), drained(process.stderr)]);
  process.exit(code);
}
