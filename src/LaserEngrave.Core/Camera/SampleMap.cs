namespace LaserEngrave.Core.Camera;

/// <summary>One frame of a map: where the stage stood, µm, and what the camera saw.</summary>
public sealed record MapFrame(double StageXUm, double StageYUm, CameraFrame Frame);

/// <summary>How well two neighbouring frames meet: the picture shift the calibration predicts between them, the one measured, and their difference, camera pixels.</summary>
public readonly record struct MapSeam(int First, int Second, double PredictedXPx, double PredictedYPx, double MeasuredXPx, double MeasuredYPx)
{
    public double ErrorPx => Math.Sqrt(Math.Pow(MeasuredXPx - PredictedXPx, 2) + Math.Pow(MeasuredYPx - PredictedYPx, 2));
}

/// <summary>A stitched overview of the sample in stage axes: map pixel (0, 0) is centred at (<see cref="OriginXUm"/>, <see cref="OriginYUm"/>), x along stage X, y along stage Y.</summary>
public sealed record SampleMap(CameraFrame Image, double OriginXUm, double OriginYUm, double UmPerPixel, IReadOnlyList<MapFrame> Frames, IReadOnlyList<MapSeam> Seams)
{
    /// <summary>The worst seam, camera pixels (0 for a single frame).</summary>
    public double WorstSeamPx => Seams.Count == 0 ? 0 : Seams.Max(s => s.ErrorPx);
}
