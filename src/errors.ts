/**
 * The one error type Lantern throws for problems a user can fix (bad input, missing adapter, absurd
 * sizes). `message` says what is wrong; `hint` says what to do. Front ends (CLI, page) print these as
 * one line and keep stack traces for `--verbose`; anything that is not a LanternError is a bug.
 */
export class LanternError extends Error {
  constructor(
    message: string,
    readonly hint?: string,
    options?: { cause?: unknown },
  ) {
    super(message, options);
    this.name = 'LanternError';
  }

  /** "What is wrong. What to do", the one line a user sees. */
  get userMessage(): string {
    if (!this.hint) return this.message;
    return `${this.message}. ${this.hint.charAt(0).toUpperCase()}${this.hint.slice(1)}`;
  }
}
