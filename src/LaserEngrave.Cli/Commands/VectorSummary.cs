using System.Globalization;
using LaserEngrave.Core.Jobs;
using LaserEngrave.Core.Vectors;

namespace LaserEngrave.Cli.Commands;

/// <summary>The figures of a vector plan, as `plan --json` prints them for a drawing.</summary>
internal sealed record VectorSummary(
    string Drawing,
    double WidthMm,
    double HeightMm,
    double Scale,
    double ToleranceUm,
    int PathCount,
    int OutlineCount,
    int FillRows,
    long Vertices,
    double BurnLengthMm,
    double TravelMm,
    double TravelDrawingOrderMm,
    double TravelSavedPercent,
    bool FitsTravel,
    IReadOnlyList<string> Warnings,
    int Strokes,
    double EstimatedSeconds,
    double EstimatedEngravingSeconds,
    double PredictedDeviationUm)
{
    public static VectorSummary From(PreparedDrawing drawing)
    {
        var plan = drawing.Plan;
        return From(plan) with
        {
            FitsTravel = drawing.FitsTravel,
            Warnings = drawing.Warnings,
            Strokes = drawing.Schedule.Strokes.Count,
            EstimatedSeconds = drawing.WholeRunSeconds(drawing.Spec.Passes),
            EstimatedEngravingSeconds = drawing.Schedule.EstimatedSeconds * drawing.Spec.Passes,
            PredictedDeviationUm = drawing.Schedule.PredictedDeviationUm,
        };
    }

    public static VectorSummary From(VectorPlan plan) => new(
        plan.DrawingPath,
        plan.WidthMm,
        plan.HeightMm,
        plan.Scale,
        plan.ToleranceUm,
        plan.Paths.Count,
        plan.OutlineCount,
        plan.FillRows.Count,
        plan.Paths.Sum(p => (long)p.Points.Count),
        plan.BurnLengthMm,
        plan.TravelMm,
        plan.TravelDrawingOrderMm,
        plan.TravelSavedPercent,
        plan.FitsTravel,
        plan.Warnings,
        0,
        0,
        0,
        0);

    public void WriteText(TextWriter output)
    {
        var c = CultureInfo.InvariantCulture;
        output.WriteLine(string.Create(c, $"Drawing:          {Drawing}"));
        output.WriteLine(string.Create(c, $"Size on stage:    {WidthMm:0.####} x {HeightMm:0.####} mm (scale {Scale:0.######})"));
        output.WriteLine(string.Create(c, $"Paths:            {PathCount} ({OutlineCount} outlines, {FillRows} fill rows), {Vertices} vertices within {ToleranceUm:0.###} µm"));
        output.WriteLine(string.Create(c, $"Burn length:      {BurnLengthMm:0.###} mm"));
        output.WriteLine(string.Create(c, $"Travel:           {TravelMm:0.###} mm ({TravelDrawingOrderMm:0.###} mm in drawing order, {TravelSavedPercent:0.#} % saved)"));
        if (Strokes > 0)
        {
            output.WriteLine(string.Create(c, $"Strokes:          {Strokes} (each axis streaming its speed; the model within {PredictedDeviationUm:0.##} µm of the path)"));
            output.WriteLine(string.Create(c, $"Estimated time:   {Core.Logging.RunSummaryText.Duration(EstimatedSeconds)} ({EstimatedSeconds:0.##} s, the whole run); engraving {Core.Logging.RunSummaryText.Duration(EstimatedEngravingSeconds)} ({EstimatedEngravingSeconds:0.##} s)"));
        }

        output.WriteLine(string.Create(c, $"Fits the travel:  {(FitsTravel ? "yes" : "NO")}"));
    }
}
