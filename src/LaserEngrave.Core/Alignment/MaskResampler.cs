using LaserEngrave.Core.Calibration;
using LaserEngrave.Core.Geometry;
using LaserEngrave.Core.Imaging;

namespace LaserEngrave.Core.Alignment;

/// <summary>A job mask turned into the stage's frame, so its rows run along the stage's X axis, and where to put it.</summary>
/// <param name="Mask">The resampled mask, same pitch as the job.</param>
/// <param name="OriginXMm">Stage X of the resampled mask's top-left corner (for --origin-mm), mm.</param>
/// <param name="OriginYMm">Stage Y of the resampled mask's top-left corner, mm.</param>
public sealed record AlignedMask(BitMask Mask, double OriginXMm, double OriginYMm);

/// <summary>Resamples a job mask under a rigid transform onto an axis-aligned grid of the same pitch (nearest neighbour).</summary>
/// <remarks>
/// The new grid covers the transformed job's bounding box, starting at its smallest true x and y. Each new pixel takes
/// the job pixel under its centre: centre c, job point j = T⁻¹(c), pixel (floor(j.x / p), floor(j.y / p)); outside the
/// job it stays white. A 1-bit mask has no grey to interpolate, and nearest neighbour keeps every line's width to within
/// a pixel. Rows stay single-axis moves: the rotation is in the mask, not in the motion.
/// </remarks>
public static class MaskResampler
{
    public static AlignedMask Resample(BitMask mask, double pitchUm, RigidTransform transform, AxisCalibration? calibration = null)
    {
        ArgumentNullException.ThrowIfNull(mask);
        if (!(pitchUm > 0) || double.IsInfinity(pitchUm))
        {
            throw new AlignmentException($"pitch {pitchUm} µm must be a finite number above 0");
        }

        var p = Units.UmToMm(pitchUm);
        double w = mask.Width * p, h = mask.Height * p;
        var corners = new[] { transform.Apply(0, 0), transform.Apply(w, 0), transform.Apply(w, h), transform.Apply(0, h) };
        var minX = corners.Min(c => c.X);
        var minY = corners.Min(c => c.Y);

        // A hair below whole keeps a 90° turn (cos 90° = 6e-17, not 0) from growing the grid by a pixel.
        var width = (int)Math.Ceiling(((corners.Max(c => c.X) - minX) / p) - 1e-9);
        var height = (int)Math.Ceiling(((corners.Max(c => c.Y) - minY) / p) - 1e-9);
        if ((long)width * height > BitMask.MaxPixels || width > BitMask.MaxSide || height > BitMask.MaxSide)
        {
            throw new AlignmentException($"the rotated job needs {width} x {height} pixels, more than a mask holds");
        }

        var result = new BitMask(Math.Max(1, width), Math.Max(1, height));
        var (s, c) = Math.SinCos(transform.AngleRadians);
        for (var row = 0; row < result.Height; row++)
        {
            var cy = minY + ((row + 0.5) * p) - transform.TranslationYMm;
            for (var column = 0; column < result.Width; column++)
            {
                var cx = minX + ((column + 0.5) * p) - transform.TranslationXMm;
                var jx = Math.Floor(((c * cx) + (s * cy)) / p);
                var jy = Math.Floor(((-s * cx) + (c * cy)) / p);
                if (jx >= 0 && jy >= 0 && jx < mask.Width && jy < mask.Height && mask[(int)jx, (int)jy])
                {
                    result[column, row] = true;
                }
            }
        }

        // The grid's corner is a true position; the stage is sent M⁻¹ of it on a calibrated machine.
        var (ox, oy) = new StageCompensation(calibration ?? AxisCalibration.None).ToStage(minX, minY);
        return new AlignedMask(result, ox, oy);
    }
}
