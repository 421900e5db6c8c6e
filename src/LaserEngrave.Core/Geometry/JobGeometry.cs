
namespace LaserEngrave.Core.Geometry;

/// <summary>Where each pixel of a job lands on the stage: the unrounded pitch and origin in microsteps, and the one rounding rule.</summary>
/// <remarks>
/// x grows to the right of the image and y down it (row 0 first). With p = <see cref="PitchMicrosteps"/> and
/// (ox, oy) = the origin, all unrounded, the run of pixels [c0, c1) of row r burns along y = round(oy + (r + 0.5) p)
/// from x = round(ox + c0 p) to x = round(ox + c1 p). Every position is computed from these absolute values and
/// rounded once, half away from zero (<see cref="MidpointRounding.AwayFromZero"/>); rounded steps are never added
/// up, so the error of any edge is at most half a microstep however many runs precede it (seed 001's lesson).
/// <para>
/// With a <see cref="Compensation"/> (a calibrated machine, docs/calibration.md) the pixel grid is laid out in true
/// coordinates and mapped to stage coordinates before the one rounding: edge x of column c on row r is
/// round(ox + c p / ax + (r + 0.5) p tan g / ax) and the row's y is round(oy + (r + 0.5) p / (by cos g)). The job's
/// origin is the fixed point, so it stays where it was asked for. Without a calibration the factors are exactly 1 and 0
/// and every position is the same as above, bit for bit.
/// </para>
/// </remarks>
public sealed record JobGeometry
{
    public JobGeometry(
        int widthPx,
        int heightPx,
        double pitchMicrosteps,
        double originXMicrosteps,
        double originYMicrosteps,
        double microstepUm,
        long travelXMicrosteps,
        long travelYMicrosteps,
        StageCompensation? compensation = null)
    {
        if (widthPx <= 0 || heightPx <= 0)
        {
            throw new GeometryException($"an image of {widthPx} x {heightPx} pixels has no area");
        }

        if (!(pitchMicrosteps > 0) || double.IsInfinity(pitchMicrosteps))
        {
            throw new GeometryException($"pitch {pitchMicrosteps} microsteps must be a finite number above 0");
        }

        if (!double.IsFinite(originXMicrosteps) || !double.IsFinite(originYMicrosteps))
        {
            throw new GeometryException($"origin ({originXMicrosteps}, {originYMicrosteps}) microsteps must be finite");
        }

        if (!(microstepUm > 0) || double.IsInfinity(microstepUm))
        {
            throw new GeometryException($"microstep {microstepUm} µm must be a finite number above 0");
        }

        if (travelXMicrosteps <= 0 || travelYMicrosteps <= 0)
        {
            throw new GeometryException($"stage travel {travelXMicrosteps} x {travelYMicrosteps} microsteps must be above 0");
        }

        // Keeps every position well inside long and every product c * p exact enough in a double (< 2^52).
        const double Limit = 1L << 52;
        if (Math.Abs(originXMicrosteps) + (widthPx * pitchMicrosteps) > Limit
            || Math.Abs(originYMicrosteps) + (heightPx * pitchMicrosteps) > Limit)
        {
            throw new GeometryException($"a job of {widthPx} x {heightPx} pixels at {pitchMicrosteps} microsteps per pixel is too large to place");
        }

        WidthPx = widthPx;
        HeightPx = heightPx;
        PitchMicrosteps = pitchMicrosteps;
        OriginXMicrosteps = originXMicrosteps;
        OriginYMicrosteps = originYMicrosteps;
        MicrostepUm = microstepUm;
        TravelXMicrosteps = travelXMicrosteps;
        TravelYMicrosteps = travelYMicrosteps;
        Compensation = compensation ?? StageCompensation.Identity;
        PitchXMicrosteps = pitchMicrosteps * Compensation.XPerX;
        ShearXMicrosteps = pitchMicrosteps * Compensation.XPerY;
        PitchYMicrosteps = pitchMicrosteps * Compensation.YPerY;
    }

    public int WidthPx { get; }

    public int HeightPx { get; }

    /// <summary>Pixel pitch in microsteps, unrounded (need not be whole).</summary>
    public double PitchMicrosteps { get; }

    /// <summary>Stage X of the image's left edge, microsteps, unrounded.</summary>
    public double OriginXMicrosteps { get; }

    /// <summary>Stage Y of the image's top edge, microsteps, unrounded.</summary>
    public double OriginYMicrosteps { get; }

    /// <summary>Length of one microstep in µm (the same on both axes).</summary>
    public double MicrostepUm { get; }

    /// <summary>Highest X position the stage accepts, microsteps (positions run 0..this).</summary>
    public long TravelXMicrosteps { get; }

    /// <summary>Highest Y position the stage accepts, microsteps (positions run 0..this).</summary>
    public long TravelYMicrosteps { get; }

    /// <summary>The machine's squareness and scale compensation (identity when the profile is not calibrated).</summary>
    public StageCompensation Compensation { get; }

    /// <summary>Stage X per pixel column, microsteps: the pitch over the X scale.</summary>
    public double PitchXMicrosteps { get; }

    /// <summary>Stage X shift per pixel row, microsteps: the pitch times tan(squareness) over the X scale (0 when square).</summary>
    public double ShearXMicrosteps { get; }

    /// <summary>Stage Y per pixel row, microsteps: the pitch over the Y scale and cos(squareness).</summary>
    public double PitchYMicrosteps { get; }

    public double PitchUm => PitchMicrosteps * MicrostepUm;

    /// <summary>Rounds a position in microsteps to the whole microstep the stage is sent: half away from zero.</summary>
    public static long Round(double microsteps) => (long)Math.Round(microsteps, MidpointRounding.AwayFromZero);

    /// <summary>Stage X of the left edge of pixel column <paramref name="column"/> (0..WidthPx; WidthPx is the right edge of the image).</summary>
    /// <remarks>A fused multiply-add rounds ox + c p once instead of twice, so the edge is as exact as a double allows.</remarks>
    /// <remarks>On a calibrated machine this is the column's edge on the image's top edge; rows below are shifted by the shear (<see cref="RunEdgeX"/>).</remarks>
    public long EdgeX(long column) => Round(Math.FusedMultiplyAdd(column, PitchXMicrosteps, OriginXMicrosteps));

    /// <summary>Stage X of the left edge of column <paramref name="column"/> at the top edge of row <paramref name="rowEdge"/> (a corner of the pixel grid).</summary>
    public long EdgeX(long column, long rowEdge) =>
        Round(Math.FusedMultiplyAdd(column, PitchXMicrosteps, Math.FusedMultiplyAdd(rowEdge, ShearXMicrosteps, OriginXMicrosteps)));

    /// <summary>Stage X of the left edge of column <paramref name="column"/> on row <paramref name="row"/>'s centre line: where the planner starts and ends runs.</summary>
    public long RunEdgeX(long column, int row) =>
        Round(Math.FusedMultiplyAdd(column, PitchXMicrosteps, Math.FusedMultiplyAdd(row + 0.5, ShearXMicrosteps, OriginXMicrosteps)));

    /// <summary>
    /// <see cref="RunEdgeX(long, int)"/> shifted by <paramref name="offsetMicrosteps"/> (unrounded) before its one rounding:
    /// where a right-to-left row's edges go under a bidirectional scan offset. An offset of 0 gives the same edge, bit for bit.
    /// </summary>
    public long RunEdgeX(long column, int row, double offsetMicrosteps) =>
        Round(Math.FusedMultiplyAdd(column, PitchXMicrosteps, Math.FusedMultiplyAdd(row + 0.5, ShearXMicrosteps, OriginXMicrosteps + offsetMicrosteps)));

    /// <summary>
    /// Stage X of a point <paramref name="columns"/> pixel widths (not necessarily whole) from the image's left edge on
    /// row <paramref name="row"/>'s centre line, rounded once: where dot mode stops (a pixel's centre is column c + 0.5).
    /// </summary>
    public long PointX(double columns, int row) =>
        Round(Math.FusedMultiplyAdd(columns, PitchXMicrosteps, Math.FusedMultiplyAdd(row + 0.5, ShearXMicrosteps, OriginXMicrosteps)));

    /// <summary>Stage Y of the top edge of pixel row <paramref name="rowEdge"/> (0..HeightPx; HeightPx is the bottom edge of the image).</summary>
    public long EdgeY(long rowEdge) => Round(Math.FusedMultiplyAdd(rowEdge, PitchYMicrosteps, OriginYMicrosteps));

    /// <summary>Stage Y along which row <paramref name="row"/> burns: the row's centre line.</summary>
    public long RowY(int row) => Round(Math.FusedMultiplyAdd(row + 0.5, PitchYMicrosteps, OriginYMicrosteps));

    /// <summary>The smallest stage rectangle holding the whole pixel grid: with a shear the grid is a parallelogram.</summary>
    public (long Left, long Top, long Right, long Bottom) StageBounds()
    {
        long l0 = EdgeX(0, 0), l1 = EdgeX(0, HeightPx), r0 = EdgeX(WidthPx, 0), r1 = EdgeX(WidthPx, HeightPx);
        return (Math.Min(l0, l1), EdgeY(0), Math.Max(r0, r1), EdgeY(HeightPx));
    }
}
