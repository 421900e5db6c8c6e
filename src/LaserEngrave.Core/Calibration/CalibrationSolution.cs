using LaserEngrave.Core.Geometry;

namespace LaserEngrave.Core.Calibration;

/// <summary>One measurement against what the solved model predicts for it.</summary>
/// <param name="Name">What was measured, e.g. "x 16 mm" or "diagonal AC".</param>
/// <param name="Measured">The entered value, in <paramref name="Unit"/> (mm or °).</param>
/// <param name="Predicted">The model's value at the solution.</param>
/// <param name="Unit">"mm" or "°".</param>
/// <param name="Residual">Measured - predicted, in µm for lengths and degrees for angles.</param>
public sealed record MeasurementResidual(string Name, double Measured, double Predicted, string Unit, double Residual);

/// <summary>The solved squareness and scales with their expected uncertainty and every measurement's residual.</summary>
public sealed record CalibrationSolution
{
    /// <summary>The solved errors, with their 1-sigma uncertainties filled in.</summary>
    public required AxisCalibration Calibration { get; init; }

    public required IReadOnlyList<MeasurementResidual> Residuals { get; init; }

    /// <summary>Measurements minus unknowns (3); 0 means exactly determined and every residual is 0.</summary>
    public required int DegreesOfFreedom { get; init; }

    /// <summary>
    /// Root mean square of the residuals in units of their stated uncertainty, over the degrees of freedom (null when 0):
    /// about 1 when the measurements scatter as stated, well above 1 when one is wrong or the uncertainty too small.
    /// </summary>
    public double? NormalizedRms { get; init; }

    /// <summary>Root mean square of the length residuals, µm (0 when there are none).</summary>
    public required double LengthRmsUm { get; init; }
}
