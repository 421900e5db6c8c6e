using System.CommandLine;
using System.Globalization;
using LaserEngrave.Core.Geometry;
using LaserEngrave.Core.Input;
using LaserEngrave.Core.Jobs;
using LaserEngrave.Core.Marks;
using LaserEngrave.Machines.Marks;
using LaserEngrave.Simulator.Marks;

namespace LaserEngrave.Cli.Commands;

/// <summary>
/// `laserengrave mark TEXT --code datamatrix --size-mm 2 --copies 10 --out DIR [--check]`: sample IDs as a job of layers
/// (codes as images, text as strokes), numbered from the counter, each code proven readable on the twin before the burn;
/// `engrave --job DIR/job.json` burns them and advances the counter when the run completes (docs/marking.md).
/// </summary>
internal static class MarkCommand
{
    public static Command Create()
    {
        var text = new Argument<string?>("TEXT") { Description = $"The mark's text, with placeholders {MarkText.Placeholders}; or give --marks FILE", Arity = ArgumentArity.ZeroOrOne };
        var marks = new Option<string?>("--marks") { Description = "A marks file (JSON, the fields of docs/marking.md) instead of TEXT and the options" };
        var code = new Option<string?>("--code") { Description = "qr, datamatrix, or none for a text alone (default none)" };
        var sizeMm = new Option<double?>("--size-mm") { Description = "The code's side without its quiet zone, mm (or --module-um)" };
        var moduleUm = new Option<double?>("--module-um") { Description = "A module's side, µm (or --size-mm); at least the spot's diameter" };
        var quiet = new Option<int?>("--quiet") { Description = "Quiet zone, modules (default 4 for QR, 1 for Data Matrix)" };
        var ecc = new Option<string?>("--ecc") { Description = "QR error correction: L, M (default), Q or H" };
        var noLabel = new Option<bool>("--no-label") { Description = "No text beneath the code" };
        var textHeight = new Option<double?>("--text-height-mm") { Description = "Capital height of the text, mm (default 0.4)" };
        var align = new Option<string?>("--align") { Description = "left, center (default) or right" };
        var lineSpacing = new Option<double?>("--line-spacing") { Description = "Baseline to baseline, text heights (default 1.6)" };
        var font = new Option<string?>("--font") { Description = "An installed system font, filled as raster (default: the engraving font's single strokes)" };
        var copies = new Option<int?>("--copies") { Description = $"Copies on a grid, each with its own number (1..{MarkSpec.MaxCopies})" };
        var columns = new Option<int?>("--columns") { Description = "Copies in a row (default all, up to 10)" };
        var pitch = new Option<string?>("--pitch-mm") { Description = "From copy to copy, X,Y mm (default the copy's size plus 1 mm)" };
        var origin = new Option<string?>("--origin-mm") { Description = "The first copy's top-left corner, X,Y mm (default 10,10)" };
        var speed = new Option<double?>("--speed-mm-s") { Description = "Burn speed, mm/s (default the profile's)" };
        var frequency = new Option<double?>("--frequency-hz") { Description = "Laser frequency, Hz (default the profile's)" };
        var passes = new Option<int?>("--passes") { Description = "Passes of every layer (default 1)" };
        var sample = new Option<string?>("--sample") { Description = "The sample ID that {sample} stands for" };
        var profile = new Option<string?>("--profile") { Description = "Machine profile (JSON): the spot, the process, the travel" };
        var counter = new Option<string?>("--counter") { Description = $"The sample counter (default {MarkCounter.FileName} with the app's settings)" };
        var start = new Option<int?>("--start") { Description = "Set the counter's next number first (a new batch)" };
        var output = new Option<string>("--out") { Description = "Folder for the job: job.json, marks.json and each mark's files", Required = true };
        var check = new Option<bool>("--check") { Description = "Burn every code on the twin and read it back with ZXing; refuse the job if one does not read" };
        var smallest = new Option<bool>("--smallest") { Description = "With --check: also find the smallest module that still reads on the twin" };
        var json = new Option<bool>("--json") { Description = "Print the marks, the estimate and the verdicts as JSON" };
        var command = new Command("mark", "Make sample IDs (QR, Data Matrix, text) numbered from the counter into a job of layers, and prove the codes readable on the twin")
        {
            text, marks, code, sizeMm, moduleUm, quiet, ecc, noLabel, textHeight, align, lineSpacing, font, copies, columns, pitch, origin,
            speed, frequency, passes, sample, profile, counter, start, output, check, smallest, json,
        };
        Option[] specOptions = [code, sizeMm, moduleUm, quiet, ecc, noLabel, textHeight, align, lineSpacing, font, copies, columns, pitch, origin, speed, frequency, passes];
        command.SetAction(async (result, ct) =>
        {
            var stdout = result.InvocationConfiguration.Output;
            MarkSpec spec;
            if (result.GetValue(marks) is { } marksFile)
            {
                if (result.GetValue(text) is not null || specOptions.Any(o => OptionChecks.IsGiven(result, o)))
                {
                    throw new UsageException($"--marks {marksFile}: give the mark in the file or on the command line, not both");
                }

                spec = MarkFile.Load(marksFile);
            }
            else
            {
                var template = result.GetValue(text) ?? throw new UsageException("give the mark's TEXT, or --marks FILE");
                var kind = result.GetValue(code) is { } c
                    ? MarkFile.ParseCode(c) ?? (c.Trim().Equals("none", StringComparison.OrdinalIgnoreCase) ? null : throw new UsageException($"--code {c}: not qr, datamatrix or none"))
                    : null;
                var p = result.GetValue(pitch) is { } pitchText ? Pair(pitchText, "--pitch-mm") : ((double, double)?)null;
                spec = new MarkSpec
                {
                    Text = template,
                    Code = kind,
                    SizeMm = result.GetValue(sizeMm),
                    ModuleUm = result.GetValue(moduleUm),
                    QuietModules = result.GetValue(quiet),
                    ErrorCorrection = result.GetValue(ecc) is { } e ? e.Trim().Length == 1 ? e.Trim()[0] : throw new UsageException($"--ecc {e}: not L, M, Q or H") : null,
                    Label = !result.GetValue(noLabel),
                    TextHeightMm = result.GetValue(textHeight) ?? 0.4,
                    Align = result.GetValue(align) is { } a ? MarkFile.ParseAlign(a) ?? throw new UsageException($"--align {a}: not left, center or right") : TextAlign.Center,
                    LineSpacing = result.GetValue(lineSpacing) ?? 1.6,
                    Font = result.GetValue(font),
                    Copies = result.GetValue(copies) ?? 1,
                    Columns = result.GetValue(columns),
                    PitchXMm = p?.Item1,
                    PitchYMm = p?.Item2,
                    Origin = result.GetValue(origin) is { } o ? JobOptions.ParseOrigin(o) : new OriginMm(10, 10),
                    SpeedMmPerS = result.GetValue(speed),
                    FrequencyHz = result.GetValue(frequency),
                    Passes = result.GetValue(passes) ?? 1,
                };
            }

            if (result.GetValue(smallest) && !result.GetValue(check))
            {
                throw new UsageException("--smallest needs --check: both burn on the twin");
            }

            var machine = result.GetValue(profile) is { } profilePath ? MachineProfile.Load(profilePath) : MachineProfile.Default;
            var counterFile = new MarkCounter(result.GetValue(counter) ?? DefaultCounterPath());
            if (result.GetValue(start) is { } first)
            {
                MarkCounter.Check(first);
            }

            var folder = result.GetValue(output)!;
            if (File.Exists(folder))
            {
                throw new UsageException($"--out {folder}: is a file; give a folder");
            }

            if (Directory.Exists(folder) && File.Exists(Path.Combine(folder, MarkLayout.JobFileName)) && !File.Exists(Path.Combine(folder, MarkLayout.ManifestFileName)))
            {
                throw new UsageException($"--out {folder}: holds a job that is not one of marks; give another folder");
            }

            var marksPath = result.GetValue(marks);
            var order = new MarkOrder(spec, counterFile, new MarkContext(0, result.GetValue(sample), DateTimeOffset.Now, machine.Name), machine, folder)
            {
                StartAt = result.GetValue(start),
                // A mark from the command line is refused in its options' names; one from a marks file in the file's.
                Name = marksPath is null ? OptionName : null,
                Check = result.GetValue(check),
                Smallest = result.GetValue(smallest),
            };
            MadeMarks made;
            try
            {
                made = await MarkMaking.MakeAsync(order, ct).ConfigureAwait(false);
            }
            catch (MarkException ex) when (marksPath is not null)
            {
                throw new MarkException($"{marksPath}: {ex.Message}", ex);
            }

            var unreadable = made.Unreadable;
            var summary = new MarkSummary(
                made.JobFile,
                made.Layout.FirstNumber,
                spec.Copies,
                Path.GetFullPath(counterFile.Path),
                made.Layout.Marks,
                made.Job.EstimatedSeconds,
                made.Verdicts,
                made.SmallestReadableModuleUm);
            if (result.GetValue(json))
            {
                CliJson.Write(stdout, summary);
            }
            else
            {
                WriteText(stdout, summary, machine);
            }

            if (unreadable is not null)
            {
                throw new MarkException(string.Create(CultureInfo.InvariantCulture, $"\"{unreadable.Text}\" does not read on the twin ({unreadable.ModulesRight} of {unreadable.Modules} modules right, the worst {unreadable.WorstModulePercent:0} % as it should be, at {unreadable.ModuleUm:0.#} µm modules with a {unreadable.SpotDiameterUm:0.#} µm spot); no job was written: make the mark larger"));
            }

            return CliRunner.Ok;
        });
        return command;
    }

    /// <summary>The counter beside the app's settings, so the command line and the app count the same samples.</summary>
    public static string DefaultCounterPath() =>
        Path.Combine(Environment.GetFolderPath(Environment.SpecialFolder.ApplicationData, Environment.SpecialFolderOption.Create), "LaserEngrave", MarkCounter.FileName);

    /// <summary>A marks file's field as the command line names it: the option that gives it.</summary>
    internal static string OptionName(string field) => field switch
    {
        "moduleUm" => "--module-um",
        "sizeMm" => "--size-mm",
        "quietModules" => "--quiet",
        "errorCorrection" => "--ecc",
        "textHeightMm" => "--text-height-mm",
        "lineSpacing" => "--line-spacing",
        "originMm" => "--origin-mm",
        "copies" => "--copies",
        "columns" => "--columns",
        "pitchMm" => "--pitch-mm",
        "speedMmPerS" => "--speed-mm-s",
        "frequencyHz" => "--frequency-hz",
        "passes" => "--passes",
        _ => field,
    };

    private static (double, double) Pair(string text, string name) =>
        NumberText.TryParsePair(text, out var x, out var y, out var problem) ? (x, y) : throw new UsageException($"{name} {text}: {problem}");

    private static void WriteText(TextWriter output, MarkSummary s, MachineProfile machine)
    {
        var c = CultureInfo.InvariantCulture;
        foreach (var mark in s.Marks)
        {
            output.WriteLine(string.Create(c, $"{mark.Number,4}  {mark.Kind,-10}  {mark.Text,-20}  at {mark.XMm:0.###}, {mark.YMm:0.###} mm  {mark.WidthMm:0.###} x {mark.HeightMm:0.###} mm{(mark.ModuleUm is { } m ? $"  module {m:0.#} µm" : string.Empty)}"));
        }

        output.WriteLine(string.Create(c, $"Estimate:         {s.EstimatedSeconds:0.#} s for {s.Copies} cop{(s.Copies == 1 ? "y" : "ies")}"));
        foreach (var v in s.Verdicts)
        {
            output.WriteLine(string.Create(c, $"Twin:             \"{v.Text}\" {(v.Reads ? "reads" : "does NOT read")}: {v.ModulesRight} of {v.Modules} modules right, worst module {v.WorstModulePercent:0} % as it should be; module {v.ModuleUm:0.#} µm = {v.ModuleUm / v.SpotDiameterUm:0.##} spots; twin {v.TwinSeconds:0.#} s, estimate {v.EstimatedSeconds:0.#} s"));
        }

        if (s.SmallestReadableModuleUm is { } smallest)
        {
            output.WriteLine(string.Create(c, $"Smallest module:  {smallest:0.#} µm still reads on the twin ({smallest / machine.SpotDiameterUm:0.##} spots of {machine.SpotDiameterUm:0.#} µm)"));
        }

        output.WriteLine(s.JobFile is { } job
            ? $"Job:              {job}  (burn it: laserengrave engrave --job {job} --simulate, or on the ports; the counter advances when the run completes)"
            : "Job:              not written");
        output.WriteLine(string.Create(c, $"Counter:          {s.Counter}: numbers {s.FirstNumber}..{s.FirstNumber + s.Copies - 1}"));
    }

    /// <summary>What `mark` made: the job, the numbers, every mark, the estimate and the twin's verdicts.</summary>
    internal sealed record MarkSummary(
        string? JobFile,
        int FirstNumber,
        int Copies,
        string Counter,
        IReadOnlyList<PlacedMark> Marks,
        double EstimatedSeconds,
        IReadOnlyList<ReadabilityVerdict> Verdicts,
        double? SmallestReadableModuleUm);
}
