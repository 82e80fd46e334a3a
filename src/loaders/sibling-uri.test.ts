import { describe, expect, it } from 'vitest';
import { siblingPath } from './sibling-uri.ts';

const path = (uri: string) => {
  const r = siblingPath(uri);
  return r.ok ? r.path : `refused: ${r.reason}`;
};

describe('siblingPath: what a model may name', () => {
  it('takes files in the folder and below, decoded and folded', () => {
    expect(path('model.bin')).toBe('model.bin');
    expect(path('./textures/wood.png')).toBe('textures/wood.png');
    expect(path('textures//wood.png')).toBe('textures/wood.png');
    expect(path('my%20wood.png')).toBe('my wood.png');
    expect(path('textures\\wood.png')).toBe('textures/wood.png');
    // Down and back up again stays inside.
    expect(path('textures/../model.bin')).toBe('model.bin');
    // A lone '%' is part of the name.
    expect(path('100%.png')).toBe('100%.png');
  });

  it('refuses what leaves the folder, however it is spelt', () => {
    for (const uri of ['../model.bin', '../../../../../../etc/hostname', 'textures/../../x.bin', '%2e%2e/%2e%2e/etc/hostname', '..%2f..%2fetc%2fhostname', '..\\..\\etc\\hostname']) {
      expect(path(uri), uri).toBe("refused: it leads out of the model's folder");
    }
  });

  it('refuses absolute paths, drives and shares', () => {
    for (const uri of ['/etc/hostname', '%2fetc%2fhostname', 'C:\\Windows\\win.ini', 'c:/x.bin', '//server/share/x.bin', '\\\\server\\share\\x.bin']) {
      expect(path(uri), uri).toBe('refused: it is an absolute path');
    }
  });

  it('refuses URLs of any scheme: no other file of the machine, no network', () => {
    expect(path('file:///etc/hostname')).toBe('refused: it is a URL (file:), not a path beside the model');
    expect(path('http://127.0.0.1:8080/x.bin')).toBe('refused: it is a URL (http:), not a path beside the model');
    expect(path('HTTPS://example.com/x.png')).toBe('refused: it is a URL (https:), not a path beside the model');
  });

  it('refuses names that are no file', () => {
    expect(path('')).toBe('refused: it is empty');
    expect(path('.')).toBe('refused: it names the folder, not a file');
    expect(path('textures/..')).toBe('refused: it names the folder, not a file');
    expect(path('a%00.png')).toBe('refused: it holds a NUL character');
  });
});
