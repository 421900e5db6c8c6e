using System.Globalization;
using System.Text;

namespace LaserEngrave.App.Services;

/// <summary>One run as the app's history keeps it: who, what, with which settings, and how it ended.</summary>
public sealed record RunRecord
{
    public required string Id { get; init; }

    public required DateTimeOffset StartedUtc { get; init; }

    public DateTimeOffset? FinishedUtc { get; init; }

    /// <summary>"completed", "aborted" or "failed".</summary>
    public required string Outcome { get; init; }

    /// <summary>The error of a failed run.</summary>
    public string? Error { get; init; }

    public string? SampleId { get; init; }

    public string? Notes { get; init; }

    public required string Machine { get; init; }

    public string? ImageSha256 { get; init; }

    public required JobSettings Settings { get; init; }

    public double AchievedWidthMm { get; init; }

    public double AchievedHeightMm { get; init; }

    public double EstimatedSeconds { get; init; }

    public long MovesDone { get; init; }

    public long MovesTotal { get; init; }

    public int PassesDone { get; init; }

    public double ElapsedSeconds => FinishedUtc is { } end ? (end - StartedUtc).TotalSeconds : 0;

    /// <summary>The summary as text, one value a line, for the export and the page.</summary>
    public string ToText()
    {
        var c = CultureInfo.InvariantCulture;
        var s = Settings;
        var text = new StringBuilder();
        text.AppendLine(c, $"LaserEngrave run {Id}");
        text.AppendLine(c, $"started      {StartedUtc:u}");
        text.AppendLine(c, $"finished     {FinishedUtc:u}");
        text.AppendLine(c, $"outcome      {Outcome}{(Error is null ? string.Empty : ": " + Error)}");
        text.AppendLine(c, $"sample       {SampleId}");
        text.AppendLine(c, $"notes        {Notes}");
        text.AppendLine(c, $"machine      {Machine}");
        text.AppendLine(c, $"image        {s.ImagePath}");
        text.AppendLine(c, $"image sha256 {ImageSha256}");
        text.AppendLine(c, $"mask         threshold {s.ThresholdPercent} %, dither {s.Dither}, invert {s.Invert}");
        text.AppendLine(c, $"size         {AchievedWidthMm:0.####} x {AchievedHeightMm:0.####} mm, pitch {s.PitchUm:0.###} µm, origin ({s.OriginXMm}, {s.OriginYMm}) mm");
        text.AppendLine(c, $"process      {s.LaserFrequencyHz} Hz, burn {s.BurnSpeedMmPerS} mm/s, travel {s.TravelSpeedMmPerS} mm/s, acceleration {s.AccelerationMmPerS2} mm/s²");
        text.AppendLine(c, $"plan         {s.Strategy}, bidirectional {s.Bidirectional}, overscan {s.OverscanMm} mm, passes {s.Passes}");
        text.AppendLine(c, $"moves        {MovesDone} of {MovesTotal}, passes done {PassesDone}");
        text.AppendLine(c, $"time         {ElapsedSeconds:0.0} s (estimated {EstimatedSeconds:0.0} s)");
        return text.ToString();
    }
}
