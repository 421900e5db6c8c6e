using System.CommandLine;
using System.Globalization;
using LaserEngrave.Core.Geometry;
using LaserEngrave.Core.Process;

namespace LaserEngrave.Cli.Commands;

/// <summary>`laserengrave process ...`: seed 004's pulse arithmetic; solves v = D f / N for the one quantity left out.</summary>
internal static class ProcessCommand
{
    public static Command Create()
    {
        var speed = new Option<double?>("--speed-mm-s") { Description = "Stage speed while burning, mm/s" };
        var frequency = new Option<double?>("--frequency-hz") { Description = "Laser pulse frequency, Hz" };
        var spacing = new Option<double?>("--spacing-um") { Description = "Distance between pulses (dots), µm" };
        var overlap = new Option<double?>("--overlap-percent") { Description = "Overlap of successive pulses, % of the spot (instead of --spacing-um)" };
        var pulsesPerDot = new Option<int?>("--pulses-per-dot") { Description = "Pulses fired per dot (default 1; solved when speed, frequency and spacing are all given)" };
        var spot = new Option<double?>("--spot-um") { Description = "Focused spot diameter, µm (default: the profile's)" };
        var pitch = new Option<double?>("--pitch-um") { Description = "Pixel pitch, µm, for the pulses and energy per pixel" };
        var energy = new Option<double?>("--pulse-energy-uj") { Description = "Energy of one pulse, µJ, for the energy per pixel" };
        var profile = new Option<string?>("--profile") { Description = "Machine profile (JSON) for the spot diameter; default: two Zaber T-LA60A" };
        var json = new Option<bool>("--json") { Description = "Print one JSON object" };
        var command = new Command(
            "process",
            "Pulse arithmetic: give two of speed, frequency and spacing (or overlap) and it solves the third; prints overlap and pulses per pixel");
        foreach (var option in new Option[] { speed, frequency, spacing, overlap, pulsesPerDot, spot, pitch, energy, profile, json })
        {
            command.Options.Add(option);
        }

        command.SetAction(result =>
        {
            var machine = result.GetValue(profile) is { } path ? MachineProfile.Load(path) : MachineProfile.Default;
            var spotUm = result.GetValue(spot) ?? machine.SpotDiameterUm;
            var query = new ProcessQuery
            {
                SpeedMmPerS = result.GetValue(speed),
                FrequencyHz = result.GetValue(frequency),
                SpacingUm = result.GetValue(spacing),
                OverlapPercent = result.GetValue(overlap),
                PulsesPerDot = result.GetValue(pulsesPerDot),
                SpotDiameterUm = spotUm,
                PitchUm = result.GetValue(pitch),
                PulseEnergyUj = result.GetValue(energy),
            };
            ProcessSolution solution;
            try
            {
                solution = query.Solve();
            }
            catch (ProcessException ex)
            {
                throw new UsageException(ex.Message);
            }

            var output = result.InvocationConfiguration.Output;
            if (result.GetValue(json))
            {
                CliJson.Write(output, ProcessSummary.From(solution));
            }
            else
            {
                WriteText(output, solution);
            }

            foreach (var warning in solution.Figures.Warnings)
            {
                result.InvocationConfiguration.Error.WriteLine($"warning: {warning.Message}");
            }

            var limit = Math.Min(machine.X.MaxSpeedMmPerS, machine.Y.MaxSpeedMmPerS);
            if (solution.Figures.SpeedMmPerS > limit)
            {
                result.InvocationConfiguration.Error.WriteLine(string.Create(
                    CultureInfo.InvariantCulture,
                    $"warning: {solution.Figures.SpeedMmPerS:0.###} mm/s is above this stage's {limit:0.###} mm/s ({machine.Name})"));
            }

            return 0;
        });
        return command;
    }

    private static void WriteText(TextWriter output, ProcessSolution solution)
    {
        var f = solution.Figures;
        var c = CultureInfo.InvariantCulture;
        string Mark(ProcessQuantity q) => solution.Solved == q ? "   (solved)" : string.Empty;
        output.WriteLine(string.Create(c, $"Speed:            {f.SpeedMmPerS:0.######} mm/s = {Units.MmToM(f.SpeedMmPerS):0.######} m/s{Mark(ProcessQuantity.Speed)}"));
        output.WriteLine(string.Create(c, $"Frequency:        {f.FrequencyHz:0.###} Hz{Mark(ProcessQuantity.Frequency)}"));
        output.WriteLine(string.Create(c, $"Pulses per dot:   {f.PulsesPerDot}{Mark(ProcessQuantity.PulsesPerDot)}"));
        output.WriteLine(string.Create(c, $"Pulse spacing:    {f.PulseSpacingUm:0.######} µm{Mark(ProcessQuantity.Spacing)}"));
        output.WriteLine(string.Create(c, $"Spot:             {f.SpotDiameterUm:0.###} µm"));
        output.WriteLine(string.Create(c, $"Overlap:          {f.OverlapPercent:0.##} %{(f.OverlapPercent < 0 ? " (gaps)" : string.Empty)}"));
        if (f.PulsesPerPixel is { } perPixel)
        {
            output.WriteLine(string.Create(c, $"Pulses per pixel: {perPixel:0.###} (pitch {f.PitchUm:0.###} µm)"));
        }

        if (f.EnergyPerPixelUj is { } energy)
        {
            output.WriteLine(string.Create(c, $"Energy per pixel: {energy:0.###} µJ ({f.PulseEnergyUj:0.###} µJ per pulse)"));
        }
    }
}

/// <summary>`process --json`: every figure, which one was solved, and the warnings.</summary>
internal sealed record ProcessSummary(
    string Solved,
    double SpeedMmPerS,
    double FrequencyHz,
    int PulsesPerDot,
    double PulseSpacingUm,
    double SpotDiameterUm,
    double OverlapPercent,
    double? PitchUm,
    double? PulsesPerPixel,
    double? PulseEnergyUj,
    double? EnergyPerPixelUj,
    IReadOnlyList<string> Warnings)
{
    public static ProcessSummary From(ProcessSolution solution)
    {
        var f = solution.Figures;
        var solved = solution.Solved switch
        {
            ProcessQuantity.Speed => "speed",
            ProcessQuantity.Frequency => "frequency",
            ProcessQuantity.Spacing => "spacing",
            ProcessQuantity.PulsesPerDot => "pulsesPerDot",
            _ => "none",
        };
        return new ProcessSummary(
            solved, f.SpeedMmPerS, f.FrequencyHz, f.PulsesPerDot, f.PulseSpacingUm, f.SpotDiameterUm, f.OverlapPercent,
            f.PitchUm, f.PulsesPerPixel, f.PulseEnergyUj, f.EnergyPerPixelUj, [.. f.Warnings.Select(w => w.Message)]);
    }
}
