namespace LaserEngrave.Core.Geometry;

/// <summary>How camera pixels map onto the stage: scale, turn, mirror and the laser spot's pixel, with the fit's residual.</summary>
/// <remarks>
/// The sample point seen at pixel q (x right, y down, pixel centres at whole numbers) is the stage position P plus
/// M (q - spot), with M = <see cref="UmPerPixel"/> R(<see cref="RotationDeg"/>) F, F = diag(1, -1) when mirrored. So the
/// stage position that brings q under the spot is P + M (q - spot) (<see cref="StageTargetUm"/>): the spot burns the
/// sample point whose coordinates are the stage position.
/// </remarks>
public sealed record CameraCalibration
{
    public double UmPerPixel { get; init; }

    public double RotationDeg { get; init; }

    public bool Mirrored { get; init; }

    /// <summary>The laser spot's place in the image, x, pixels.</summary>
    public double SpotXPx { get; init; }

    /// <summary>The laser spot's place in the image, y, pixels.</summary>
    public double SpotYPx { get; init; }

    /// <summary>Root-mean-square misfit of the jogs against this calibration, µm on the sample (0 for nominal figures).</summary>
    public double ResidualUm { get; init; }

    /// <summary>The offset on the sample, µm in stage axes, from the spot to what pixel (<paramref name="xPx"/>, <paramref name="yPx"/>) shows.</summary>
    public (double XUm, double YUm) OffsetUm(double xPx, double yPx)
    {
        var (a, b, c, d) = Matrix();
        var du = xPx - SpotXPx;
        var dv = yPx - SpotYPx;
        return ((a * du) + (b * dv), (c * du) + (d * dv));
    }

    /// <summary>The pixel showing the sample point <paramref name="dxUm"/>, <paramref name="dyUm"/> µm (stage axes) from the spot.</summary>
    public (double XPx, double YPx) PixelAt(double dxUm, double dyUm)
    {
        var (a, b, c, d) = Matrix();
        var det = (a * d) - (b * c);
        return (SpotXPx + (((d * dxUm) - (b * dyUm)) / det), SpotYPx + (((-c * dxUm) + (a * dyUm)) / det));
    }

    /// <summary>Where the stage must go, µm, so that pixel (<paramref name="xPx"/>, <paramref name="yPx"/>) of an image taken at <paramref name="stageXUm"/>, <paramref name="stageYUm"/> comes under the spot.</summary>
    public (double XUm, double YUm) StageTargetUm(double stageXUm, double stageYUm, double xPx, double yPx)
    {
        var (dx, dy) = OffsetUm(xPx, yPx);
        return (stageXUm + dx, stageYUm + dy);
    }

    /// <summary>M as (a b; c d): stage µm per image pixel.</summary>
    public (double A, double B, double C, double D) Matrix()
    {
        var t = RotationDeg * Math.PI / 180;
        var (cos, sin) = (Math.Cos(t) * UmPerPixel, Math.Sin(t) * UmPerPixel);
        var f = Mirrored ? -1 : 1;
        return (cos, -sin * f, sin, cos * f);
    }
}
