using LaserEngrave.Core.Camera;
using LaserEngrave.Core.Geometry;

namespace LaserEngrave.Simulator.Camera;

/// <summary>What the CCD behind the objective sees at the twin stage's position: the sample's grain, every burn, the profile's optics, defocus blur and noise.</summary>
/// <remarks>
/// The profile's camera section gives the image size and the optics' truth (scale, turn, mirror, spot offset: the
/// nominal figures, which calibration must recover). The sample point at pixel q is P + M (q - spot) (see
/// <see cref="CameraCalibration"/>), P being the stage's position now. Burns are the pulses the recorder saw (each at
/// the stage's position at its instant, one every 1/f s from switching on) and <see cref="Marks"/> put on the sample by
/// hand; each is a Gaussian of the spot's diameter. The focus offset is Z's distance from z.focusMm +
/// <see cref="TwinCameraOptions.CameraFocusOffsetUm"/>. Deterministic: frame n of a seed is always the same.
/// </remarks>
public sealed class TwinCamera
{
    private readonly SimulatedMachine _machine;
    private readonly SampleTexture _texture;
    private readonly Lock _lock = new();
    private readonly List<SampleMark> _marks = [];
    private long _frames;

    /// <param name="optics">The camera's optics when the machine's profile has no camera section (the app's twin then shows a default camera).</param>
    public TwinCamera(SimulatedMachine machine, TwinCameraOptions? options = null, CameraProfile? optics = null)
    {
        ArgumentNullException.ThrowIfNull(machine);
        _machine = machine;
        Profile = machine.Profile.Camera ?? optics ?? throw new ArgumentException("the machine profile has no camera section", nameof(machine));
        Options = options ?? new TwinCameraOptions();
        _texture = new SampleTexture(Options.Seed);
    }

    public CameraProfile Profile { get; }

    public TwinCameraOptions Options { get; }

    /// <summary>The optics' truth: what a perfect calibration measures.</summary>
    public CameraCalibration Truth => Profile.Nominal;

    /// <summary>Marks on the sample besides the recorded burns (earlier work, lithography, the rig's test dots).</summary>
    public IReadOnlyList<SampleMark> Marks
    {
        get
        {
            lock (_lock)
            {
                return [.. _marks];
            }
        }
    }

    /// <summary>Puts a dark round mark on the sample, centred at (<paramref name="xUm"/>, <paramref name="yUm"/>) in stage µm.</summary>
    public void AddMark(double xUm, double yUm, double diameterUm, double pulses = 50)
    {
        lock (_lock)
        {
            _marks.Add(new SampleMark(xUm, yUm, diameterUm, pulses));
        }
    }

    /// <summary>The stage's position now, µm.</summary>
    public (double XUm, double YUm) StagePositionUm()
    {
        var now = _machine.NowSeconds;
        var r = _machine.Recorder;
        return (r.X.PositionAt(now) * r.XMicrostepUm, r.Y.PositionAt(now) * r.YMicrostepUm);
    }

    /// <summary>Z's distance from the camera's sharpest focus, µm; 0 on a machine without Z.</summary>
    public double DefocusUm()
    {
        if (_machine.Profile.Z is not { } z || _machine.Recorder.Z is not { } trajectory)
        {
            return 0;
        }

        var zUm = trajectory.PositionAt(_machine.NowSeconds) * z.MicrostepUm;
        return zUm - ((z.FocusMm * 1000) + Options.CameraFocusOffsetUm);
    }

    /// <summary>The next frame at the stage's position now.</summary>
    public CameraFrame Capture()
    {
        var frame = Interlocked.Increment(ref _frames);
        var (px, py) = StagePositionUm();
        return Render(px, py, DefocusUm(), frame);
    }

    /// <summary>The frame numbered <paramref name="frameNumber"/> as seen from stage position (<paramref name="stageXUm"/>, <paramref name="stageYUm"/>) at <paramref name="defocusUm"/>.</summary>
    public CameraFrame Render(double stageXUm, double stageYUm, double defocusUm, long frameNumber)
    {
        int w = Profile.WidthPx, h = Profile.HeightPx;
        var truth = Truth;
        var (a, b, c, d) = truth.Matrix();
        var image = new double[w * h];
        // Pixel (u, v) sees the sample at P + M ((u, v) - spot): an affine map, so the texture is filled row by row.
        _texture.Fill(image, w, h, stageXUm - (a * truth.SpotXPx) - (b * truth.SpotYPx), stageYUm - (c * truth.SpotXPx) - (d * truth.SpotYPx), a, c, b, d);
        var contrast = Options.Contrast;
        for (var i = 0; i < image.Length; i++)
        {
            image[i] = 0.5 + (contrast * (image[i] - 0.5));
        }

        DrawBurns(image, w, h, truth, stageXUm, stageYUm);
        var blurUm = Math.Sqrt((Options.FocusedBlurUm * Options.FocusedBlurUm) + Math.Pow(Options.BlurPerDefocusUm * defocusUm, 2));
        // Beyond a quarter of the image a blur leaves a flat grey anyway; the cap keeps a far-off Z from costing seconds a frame.
        GaussianBlur(image, w, h, Math.Min(blurUm / truth.UmPerPixel, Math.Max(w, h) / 4.0));
        var random = new Random(unchecked((Options.Seed * 1_000_003) + (int)frameNumber));
        var pixels = new byte[w * h];
        var noise = Options.NoiseGrey;
        // One normal value per pixel (Box-Muller's cosine half), in the same order as ever: a seed's frames stay the same images.
        for (var i = 0; i < pixels.Length; i++)
        {
            var u1 = 1.0 - random.NextDouble();
            var u2 = random.NextDouble();
            pixels[i] = Grey(image[i], noise * Math.Sqrt(-2 * Math.Log(u1)) * Math.Cos(2 * Math.PI * u2));
        }

        return new CameraFrame(w, h, pixels);
    }

    // Each burn multiplies the brightness by 2^-(dose / PulsesToHalve), the dose a Gaussian of the spot's diameter (FWHM) per pulse.
    private void DrawBurns(double[] image, int w, int h, CameraCalibration truth, double stageXUm, double stageYUm)
    {
        var spotUm = _machine.Profile.SpotDiameterUm;
        var burns = new List<(double X, double Y, double DiameterUm, double Pulses)>();
        burns.AddRange(Marks.Select(m => (m.XUm, m.YUm, m.DiameterUm, m.Pulses)));
        burns.AddRange(RecordedPulses().Select(p => (p.X, p.Y, spotUm, 1.0)));
        if (burns.Count == 0)
        {
            return;
        }

        var dose = new double[w * h];
        var any = false;
        foreach (var (x, y, diameter, pulses) in burns)
        {
            var sigmaPx = diameter / 2.3548 / truth.UmPerPixel;
            var reach = Math.Max(1, (int)Math.Ceiling(3 * sigmaPx));
            var (cx, cy) = truth.PixelAt(x - stageXUm, y - stageYUm);
            if (cx < -reach || cy < -reach || cx > w + reach || cy > h + reach)
            {
                continue;
            }

            any = true;
            for (var v = Math.Max(0, (int)cy - reach); v <= Math.Min(h - 1, (int)cy + reach); v++)
            {
                for (var u = Math.Max(0, (int)cx - reach); u <= Math.Min(w - 1, (int)cx + reach); u++)
                {
                    var r2 = ((u - cx) * (u - cx)) + ((v - cy) * (v - cy));
                    dose[(v * w) + u] += pulses * Math.Exp(-r2 / (2 * sigmaPx * sigmaPx));
                }
            }
        }

        if (!any)
        {
            return;
        }

        for (var i = 0; i < image.Length; i++)
        {
            if (dose[i] > 0)
            {
                image[i] *= Math.Pow(2, -dose[i] / Options.PulsesToHalve);
            }
        }
    }

    // The Q-switch's pulses so far, each where the stage stood at its instant, µm.
    private IEnumerable<(double X, double Y)> RecordedPulses()
    {
        var recorder = _machine.Recorder;
        var now = _machine.NowSeconds;
        (double At, double Hz)? on = null;
        var periods = new List<(double From, double To, double Hz)>();
        foreach (var (at, hz) in recorder.LaserChanges.OrderBy(c => c.AtSeconds))
        {
            if (hz > 0)
            {
                on ??= (at, hz);
            }
            else if (on is { } start)
            {
                periods.Add((start.At, at, start.Hz));
                on = null;
            }
        }

        if (on is { } open)
        {
            periods.Add((open.At, now, open.Hz));
        }

        foreach (var (from, to, hz) in periods)
        {
            for (var t = from; t < to; t += 1 / hz)
            {
                yield return (recorder.X.PositionAt(t) * recorder.XMicrostepUm, recorder.Y.PositionAt(t) * recorder.YMicrostepUm);
            }
        }
    }

    private static void GaussianBlur(double[] image, int w, int h, double sigmaPx)
    {
        if (sigmaPx < 0.05)
        {
            return;
        }

        var reach = (int)Math.Ceiling(3 * sigmaPx);
        var kernel = new double[(2 * reach) + 1];
        for (var i = -reach; i <= reach; i++)
        {
            kernel[i + reach] = Math.Exp(-(i * i) / (2 * sigmaPx * sigmaPx));
        }

        var sum = kernel.Sum();
        for (var i = 0; i < kernel.Length; i++)
        {
            kernel[i] /= sum;
        }

        var temp = new double[image.Length];
        for (var v = 0; v < h; v++)
        {
            for (var u = 0; u < w; u++)
            {
                var acc = 0.0;
                var row = v * w;
                if (u >= reach && u < w - reach)
                {
                    // Away from the sides no clamping: the common case, kept to a plain multiply-add.
                    for (var k = 0; k < kernel.Length; k++)
                    {
                        acc += kernel[k] * image[row + u - reach + k];
                    }
                }
                else
                {
                    for (var k = -reach; k <= reach; k++)
                    {
                        acc += kernel[k + reach] * image[row + Math.Clamp(u + k, 0, w - 1)];
                    }
                }

                temp[(v * w) + u] = acc;
            }
        }

        for (var v = 0; v < h; v++)
        {
            for (var u = 0; u < w; u++)
            {
                var acc = 0.0;
                if (v >= reach && v < h - reach)
                {
                    for (var k = 0; k < kernel.Length; k++)
                    {
                        acc += kernel[k] * temp[((v - reach + k) * w) + u];
                    }
                }
                else
                {
                    for (var k = -reach; k <= reach; k++)
                    {
                        acc += kernel[k + reach] * temp[(Math.Clamp(v + k, 0, h - 1) * w) + u];
                    }
                }

                image[(v * w) + u] = acc;
            }
        }
    }

    private static byte Grey(double brightness, double noise)
    {
        var grey = 30 + (200 * brightness) + noise;
        return grey <= 0 ? (byte)0 : grey >= 255 ? (byte)255 : (byte)Math.Round(grey);
    }
}

/// <summary>A dark round mark on the twin's sample, stage µm, <paramref name="Pulses"/> pulses' worth of darkening at its centre.</summary>
public readonly record struct SampleMark(double XUm, double YUm, double DiameterUm, double Pulses);
