namespace LaserEngrave.Core.Camera;

/// <summary>One step of a focus sweep: the focus offset, µm from the profile's visible focus, and the sharpness there.</summary>
public readonly record struct FocusPoint(double OffsetUm, double Sharpness);

/// <summary>A focus sweep's result: every step, the sharpest step, and the peak between steps (a parabola through the best three).</summary>
public sealed record FocusSweepResult(IReadOnlyList<FocusPoint> Points, double BestStepUm, double BestOffsetUm);

/// <summary>Steps Z through a range with the laser off and finds where the camera sees sharpest.</summary>
/// <remarks>
/// The camera's sharpest Z is where the sample surface is in the camera's focus; its offset from z.focusMm (the visible
/// focus, the 0 of the focal-offset series of seed 002) says how far the series' 0 lies from what the camera calls sharp.
/// </remarks>
public sealed class FocusSweep
{
    private readonly ICameraRig _rig;

    public FocusSweep(ICameraRig rig)
    {
        ArgumentNullException.ThrowIfNull(rig);
        _rig = rig;
    }

    /// <param name="returnToStart">Z goes back to where it stood at the start (the app offers the sharpest Z instead of taking it); otherwise Z is left at the sharpest step.</param>
    /// <exception cref="CameraException">The machine has no Z axis, or the range or step is unusable.</exception>
    public async Task<FocusSweepResult> RunAsync(double fromUm, double toUm, double stepUm, CancellationToken cancellationToken, IProgress<FocusPoint>? progress = null, bool returnToStart = false)
    {
        if (!_rig.HasFocusAxis)
        {
            throw new CameraException("a focus sweep needs a focus (Z) axis, and the machine profile has none");
        }

        if (!(stepUm > 0 && double.IsFinite(fromUm) && double.IsFinite(toUm) && toUm > fromUm))
        {
            throw new CameraException($"a focus sweep needs a range from a lower to a higher offset and a step above 0 µm (got {fromUm} to {toUm} µm by {stepUm} µm)");
        }

        var count = (int)Math.Floor(((toUm - fromUm) / stepUm) + 1e-9) + 1;
        if (count < 3 || count > 201)
        {
            throw new CameraException($"a focus sweep takes 3..201 steps (got {count}): widen the range or change the step");
        }

        var points = new List<FocusPoint>();
        var start = _rig.FocusOffsetUm;
        try
        {
            for (var i = 0; i < count; i++)
            {
                var offset = fromUm + (i * stepUm);
                await _rig.MoveFocusAsync(offset, cancellationToken);
                var point = new FocusPoint(offset, FocusMeasure.Sharpness(await _rig.CaptureAsync(cancellationToken)));
                points.Add(point);
                progress?.Report(point);
            }
        }
        catch
        {
            await _rig.MoveFocusAsync(start, CancellationToken.None);
            throw;
        }

        var best = 0;
        for (var i = 1; i < points.Count; i++)
        {
            if (points[i].Sharpness > points[best].Sharpness)
            {
                best = i;
            }
        }

        var peak = points[best].OffsetUm;
        if (best > 0 && best < points.Count - 1)
        {
            var (l, m, r) = (points[best - 1].Sharpness, points[best].Sharpness, points[best + 1].Sharpness);
            var denominator = l - (2 * m) + r;
            if (denominator < 0)
            {
                peak += Math.Clamp(0.5 * (l - r) / denominator, -0.5, 0.5) * stepUm;
            }
        }

        // Z is left at the sharpest step, where the technician wants to look next, unless asked to go back.
        await _rig.MoveFocusAsync(returnToStart ? start : points[best].OffsetUm, cancellationToken);
        return new FocusSweepResult(points, points[best].OffsetUm, peak);
    }
}
