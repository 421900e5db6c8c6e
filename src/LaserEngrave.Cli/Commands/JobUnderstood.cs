using System.Globalization;
using LaserEngrave.Core.Jobs;
using LaserEngrave.Core.Planning;

namespace LaserEngrave.Cli.Commands;

/// <summary>
/// The two lines <c>engrave</c> prints before anything moves: the size and place it understood and the process it will
/// burn with, so a value read otherwise than meant (a size, an origin, a frequency) is seen before the laser fires.
/// </summary>
internal static class JobUnderstood
{
    public static IReadOnlyList<string> Lines(EngraveJob job)
    {
        ArgumentNullException.ThrowIfNull(job);
        var parts = job.Parts;
        var left = parts.Min(p => p.Spec.Origin.X);
        var top = parts.Min(p => p.Spec.Origin.Y);
        var right = parts.Max(p => p.Spec.Origin.X + p.SizeMm.WidthMm);
        var bottom = parts.Max(p => p.Spec.Origin.Y + p.SizeMm.HeightMm);
        var what = parts.Count == 1 ? $"{Path.GetFileName(parts[0].Spec.ImagePath)}" : $"{parts.Count} layers";
        var size = Inv($"job:     {what}, {N(right - left)} x {N(bottom - top)} mm, top-left corner at {N(left)}, {N(top)} mm");
        return parts.Count == 1
            ? [size, $"process: {Process(parts[0])}"]
            : [size, $"process: {Ranges(parts)}"];
    }

    /// <summary>"raster at 1 mm/s, 1000 Hz (1 µm between pulses), 2 passes, optimized, bidirectional".</summary>
    private static string Process(JobPart part)
    {
        var process = part.Spec.Process;
        var passes = part.Layer.Passes;
        var kind = part is DrawingPart ? "drawing"
            : process.Mode == PlanMode.Dots ? Inv($"dots of {process.PulsesPerDot} pulse{(process.PulsesPerDot == 1 ? string.Empty : "s")}")
            : "raster";
        var spacing = process.Mode == PlanMode.Dots ? string.Empty : Inv($" ({N(process.BurnSpeedMmPerS * 1000 / process.LaserFrequencyHz)} µm between pulses)");
        var plan = part is RasterPart { Image: var image }
            ? $", {image.Spec.Plan.Strategy.ToString().ToLowerInvariant()}{(image.Spec.Plan.Bidirectional ? ", bidirectional" : ", one direction")}"
            : string.Empty;
        var speed = process.Mode == PlanMode.Dots ? string.Empty : Inv($"at {N(process.BurnSpeedMmPerS)} mm/s, ");
        return Inv($"{kind} {speed}{N(process.LaserFrequencyHz)} Hz{spacing}, {passes} pass{(passes == 1 ? string.Empty : "es")}{plan}");
    }

    /// <summary>The layers' speeds, frequencies and passes, each as one value or a range.</summary>
    private static string Ranges(IReadOnlyList<JobPart> parts) =>
        $"{Range(parts.Select(p => p.Spec.Process.BurnSpeedMmPerS))} mm/s, {Range(parts.Select(p => p.Spec.Process.LaserFrequencyHz))} Hz, "
        + Inv($"{Range(parts.Select(p => (double)p.Layer.Passes))} passes a layer, {parts.Sum(p => p.Layer.Passes)} layer passes in all");

    private static string Range(IEnumerable<double> values)
    {
        var list = values.ToList();
        var (min, max) = (list.Min(), list.Max());
        return min == max ? N(min) : $"{N(min)}..{N(max)}";
    }

    private static string N(double value) => value.ToString("0.####", CultureInfo.InvariantCulture);

    private static string Inv(FormattableString text) => text.ToString(CultureInfo.InvariantCulture);
}
