import { describe, expect, it } from 'vitest';
import { escapeControls } from './terminal-text.ts';

describe('escapeControls', () => {
  it('writes every C0 control, DEL and C1 control as a \\u escape, and leaves printable text alone', () => {
    // A title-setting sequence, a screen clear and a CSI (C1) as a hostile lump name could hold them.
    expect(escapeControls('MAP\u001B]0;owned\u0007\u001B[2J\r\u009B31m\u007F')).toBe('MAP\\u001B]0;owned\\u0007\\u001B[2J\\u000D\\u009B31m\\u007F');
    expect(escapeControls('E1M1 «ünïcode» \u00A0 ok')).toBe('E1M1 «ünïcode» \u00A0 ok');
    for (let c = 0; c < 0x100; c++) {
      const out = escapeControls(String.fromCharCode(c));
      const control = c < 0x20 || (c >= 0x7f && c < 0xa0);
      expect(out, `U+${c.toString(16)}`).toBe(control ? `\\u${c.toString(16).toUpperCase().padStart(4, '0')}` : String.fromCharCode(c));
    }
  });

  it('keeps newlines and tabs only where asked, and JSON stays JSON with the same value', () => {
    expect(escapeControls('a\nb\tc')).toBe('a\\u000Ab\\u0009c');
    expect(escapeControls('a\nb\tc\u001B', { keepLines: true })).toBe('a\nb\tc\\u001B');
    // JSON.stringify escapes C0 itself but writes DEL and C1 raw; escaped, they read back the same.
    const value = { name: 'WALL\u009B2J\u007F\u001B', n: [1, 2] };
    const text = escapeControls(JSON.stringify(value, null, 2), { keepLines: true });
    expect(/[\u0000-\u0009\u000B-\u001F\u007F-\u009F]/.test(text)).toBe(false);
    expect(JSON.parse(text)).toEqual(value);
  });
});
