using System.CommandLine;
using LaserEngrave.Core.Geometry;
using LaserEngrave.Core.Vectors;

namespace LaserEngrave.Cli.Commands;

/// <summary>The options only drawings have: chord tolerance, fill and path order.</summary>
internal sealed class VectorOptionSet
{
    public Option<double?> ToleranceUm { get; } = new("--tolerance-um") { Description = "Drawings: largest distance between a curve and its straight segments, µm (default 1)" };

    public Option<string?> Fill { get; } = new("--fill") { Description = "Drawings: outline (default), fill (scan lines inside closed shapes, even-odd) or both" };

    public Option<double?> FillPitchUm { get; } = new("--fill-pitch-um") { Description = "Drawings: distance between fill scan lines, µm (default 20)" };

    public Option<bool> DrawingOrder { get; } = new("--drawing-order") { Description = "Drawings: burn the paths in the drawing's order, unoptimised" };

    public void AddTo(Command command)
    {
        command.Options.Add(ToleranceUm);
        command.Options.Add(Fill);
        command.Options.Add(FillPitchUm);
        command.Options.Add(DrawingOrder);
    }

    public VectorOptions Bind(ParseResult result)
    {
        var fill = result.GetValue(Fill)?.Trim().ToLowerInvariant() switch
        {
            null or "" or "outline" => VectorFillMode.Outline,
            "fill" => VectorFillMode.Fill,
            "both" => VectorFillMode.Both,
            var other => throw new UsageException($"--fill {other}: use outline, fill or both"),
        };
        var options = new VectorOptions
        {
            ToleranceUm = result.GetValue(ToleranceUm) ?? VectorOptions.Default.ToleranceUm,
            Fill = fill,
            FillPitchUm = result.GetValue(FillPitchUm) ?? VectorOptions.Default.FillPitchUm,
            Optimize = !result.GetValue(DrawingOrder),
        };
        try
        {
            options.Validate();
        }
        catch (GeometryException ex)
        {
            throw new UsageException(ex.Message.Replace("chord tolerance", "--tolerance-um", StringComparison.Ordinal).Replace("fill pitch", "--fill-pitch-um", StringComparison.Ordinal));
        }

        return options;
    }
}
