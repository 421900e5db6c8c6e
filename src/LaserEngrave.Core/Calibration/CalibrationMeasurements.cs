namespace LaserEngrave.Core.Calibration;

/// <summary>A distance measured along one axis of the pattern: its nominal length on the job and what the microscope showed, mm.</summary>
public readonly record struct ScaleMeasurement(double NominalMm, double MeasuredMm);

/// <summary>What the technician measured on an engraved calibration pattern; any subset that determines the three unknowns.</summary>
public sealed record CalibrationMeasurements
{
    /// <summary>Distances along the X groove (e.g. crossing to mark k: nominal k x spacing).</summary>
    public IReadOnlyList<ScaleMeasurement> X { get; init; } = [];

    /// <summary>Distances along the Y groove.</summary>
    public IReadOnlyList<ScaleMeasurement> Y { get; init; } = [];

    /// <summary>The square's nominal side, centre line to centre line, mm; needed for any square measurement.</summary>
    public double? SquareSideMm { get; init; }

    /// <summary>Measured sides along X (AB and DC), mm.</summary>
    public IReadOnlyList<double> SquareSidesXMm { get; init; } = [];

    /// <summary>Measured sides along Y (AD and BC), mm.</summary>
    public IReadOnlyList<double> SquareSidesYMm { get; init; } = [];

    /// <summary>Measured diagonal from the marked corner A to C, mm.</summary>
    public double? DiagonalAcMm { get; init; }

    /// <summary>Measured diagonal from B to D, mm.</summary>
    public double? DiagonalBdMm { get; init; }

    /// <summary>Measured angle between the X groove (towards +X) and the Y groove (towards +Y), degrees (90 when square).</summary>
    public double? GrooveAngleDegrees { get; init; }

    /// <summary>One standard deviation of a length measurement, µm.</summary>
    public double LengthUncertaintyUm { get; init; } = 1;

    /// <summary>One standard deviation of an angle measurement, degrees.</summary>
    public double AngleUncertaintyDegrees { get; init; } = 0.01;

    /// <summary>How many measurements there are.</summary>
    public int Count =>
        X.Count + Y.Count + SquareSidesXMm.Count + SquareSidesYMm.Count + (DiagonalAcMm is null ? 0 : 1) + (DiagonalBdMm is null ? 0 : 1) + (GrooveAngleDegrees is null ? 0 : 1);
}
