/**
 * The render settings as command-line options, derived from the schema (renderer/settings.ts): the
 * flag, help text, default shown in the help, parsing and range errors all come from a setting's
 * entry, so the CLI accepts exactly what validation and links accept.
 */
import { InvalidArgumentError, Option, type Command } from 'commander';
import { formatSettingText, parseSettingText, setAt, settingDescription, type SettingEntry, type SettingMode } from '../renderer/settings-schema.ts';
import { SETTING_ENTRIES, type RenderSettingsPatch } from '../renderer/settings.ts';

/** The settings that have a CLI flag. */
export const CLI_SETTINGS: readonly SettingEntry[] = SETTING_ENTRIES.filter((e) => e.spec.cli !== undefined);

const cliOf = (entry: SettingEntry) => {
  if (!entry.spec.cli) throw new Error(`setting ${entry.id} has no CLI flag`);
  return entry.spec.cli;
};

/** Parses one option's text as commander does, refusing what the schema refuses with a usage error naming the flag. */
export function parseCliSetting(entry: SettingEntry, text: string): unknown {
  const cli = cliOf(entry);
  const spec = entry.spec;
  // A CLI that offers fewer choices than the setting has (--debug offers no 'none') says so.
  if (spec.type === 'choice' && cli.values && !cli.values.includes(text)) throw new InvalidArgumentError(`${cli.flag} must be one of ${cli.values.join(', ')}, not '${text}'.`);
  const parsed = parseSettingText(spec, text);
  if (!parsed.ok) throw new InvalidArgumentError(`${cli.flag} ${parsed.problem}, not '${text}'.`);
  return parsed.value;
}

/** The commander option of a setting. */
export function settingOption(entry: SettingEntry): Option {
  const cli = cliOf(entry);
  const spec = entry.spec;
  const flags = `${cli.short ? `${cli.short}, ` : ''}${cli.flag}`;
  // The mode goes first ('frame mode: …'), from the setting's `mode`, as the help has always said it.
  const description = settingDescription(spec);
  if (cli.switch) return new Option(flags, description);
  const argument = cli.argument ?? `<${spec.type === 'choice' ? 'value' : 'n'}>`;
  const values = spec.type === 'choice' ? ` (${(cli.values ?? spec.values).join(', ')})` : '';
  // A default the CLI cannot spell (--debug's 'none') is what "not given" means: no need to show it.
  const spellable = spec.type !== 'choice' || !cli.values || cli.values.includes(String(spec.default));
  const shown = entry.optional || spec.default === undefined || !spellable ? '' : ` (default: ${formatSettingText(spec, spec.default)})`;
  // No commander default: an option not given leaves the setting as the renderer has it.
  return new Option(`${flags} ${argument}`, `${description}${values}${shown}`).argParser((text) => parseCliSetting(entry, text));
}

/** The mode a setting applies to alone (its schema entry's `mode`); undefined: every mode. */
export const settingMode = (entry: SettingEntry): SettingMode | undefined => entry.spec.mode;

/** Adds the options of these settings (all that have a flag unless told which) to a command. */
export function withSettingOptions(command: Command, which: (entry: SettingEntry) => boolean = () => true): Command {
  for (const entry of CLI_SETTINGS) if (which(entry)) command.addOption(settingOption(entry));
  return command;
}

/**
 * The settings the parsed options ask for, nested as RenderSettings is; only those given, except
 * that a switch not given means false (a switch is how the CLI turns a feature on).
 */
export function settingsFromOptions(options: Readonly<Record<string, unknown>>, which: (entry: SettingEntry) => boolean = () => true): RenderSettingsPatch {
  const out: Record<string, unknown> = {};
  for (const entry of CLI_SETTINGS) {
    if (!which(entry)) continue;
    const value = options[settingOption(entry).attributeName()];
    if (value !== undefined) setAt(out, entry.path, value);
    else if (entry.spec.cli?.switch) setAt(out, entry.path, false);
  }
  return out as RenderSettingsPatch;
}
