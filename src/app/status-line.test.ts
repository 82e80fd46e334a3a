import { describe, expect, it } from 'vitest';
import { fitStatus, part } from './status-line.ts';

const parts = () => [
  part(9, '12 spp'),
  part(7, '0.23 fps (4.32 s a frame)', '0.23 fps'),
  part(4, '640×400'),
  part(1, 'google swiftshader'),
  part(3, 'budget: 0.35× (software adapter, 3 fps target)', 'budget 0.35×'),
];
/** A line of at most `n` characters fits. */
const width = (n: number) => (text: string) => text.length <= n;

describe('the status line fitted to its width', () => {
  it('keeps every part, in its longest form and in order, where it fits', () => {
    const full = '12 spp · 0.23 fps (4.32 s a frame) · 640×400 · google swiftshader · budget: 0.35× (software adapter, 3 fps target)';
    expect(fitStatus(parts(), width(full.length))).toBe(full);
  });

  it('shortens, then drops, the least important parts first, and never cuts a part', () => {
    // Shorter forms first, least important first: the budget's, then the frame rate's.
    expect(fitStatus(parts(), width(110))).toBe('12 spp · 0.23 fps (4.32 s a frame) · 640×400 · google swiftshader · budget 0.35×');
    expect(fitStatus(parts(), width(75))).toBe('12 spp · 0.23 fps · 640×400 · google swiftshader · budget 0.35×');
    // Then parts go, least important first: the adapter, the budget, the size.
    expect(fitStatus(parts(), width(60))).toBe('12 spp · 0.23 fps · 640×400 · budget 0.35×');
    expect(fitStatus(parts(), width(30))).toBe('12 spp · 0.23 fps · 640×400');
    expect(fitStatus(parts(), width(20))).toBe('12 spp · 0.23 fps');
    // The most important part stays, whatever the width.
    expect(fitStatus(parts(), width(3))).toBe('12 spp');
    for (let n = 3; n < 130; n++) {
      const text = fitStatus(parts(), width(n));
      const kept = text.split(' · ');
      // What is shown is whole parts of the full line, in order.
      expect(kept.every((k) => parts().some((p) => p!.forms.includes(k)))).toBe(true);
      if (n >= 6) expect(text.length).toBeLessThanOrEqual(n);
    }
  });

  it('shortens the most important part last, once the others have gone', () => {
    const waiting = [part(10, 'compiling shaders, 2 of 8', 'compiling, 2 of 8'), part(6, 'about 20 s left', '~20 s')];
    expect(fitStatus(waiting, width(43))).toBe('compiling shaders, 2 of 8 · about 20 s left');
    expect(fitStatus(waiting, width(40))).toBe('compiling shaders, 2 of 8 · ~20 s');
    expect(fitStatus(waiting, width(30))).toBe('compiling shaders, 2 of 8');
    expect(fitStatus(waiting, width(20))).toBe('compiling, 2 of 8');
  });

  it('leaves out parts with no text, and takes the later of equally important parts out first', () => {
    expect(part(3, '', undefined)).toBeUndefined();
    expect(fitStatus([part(5, 'a'), undefined, part(5, 'bb'), part(5, 'cc')], width(6))).toBe('a · bb');
  });
});
