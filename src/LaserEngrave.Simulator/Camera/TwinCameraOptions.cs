namespace LaserEngrave.Simulator.Camera;

/// <summary>The twin camera's physics beside the profile's optics: the sample, the blur, the noise.</summary>
public sealed record TwinCameraOptions
{
    /// <summary>Seeds the sample's grain and the frames' noise: the same seed, the same images.</summary>
    public int Seed { get; init; } = 37;

    /// <summary>Standard deviation of each pixel's noise, grey levels of 255.</summary>
    public double NoiseGrey { get; init; } = 2;

    /// <summary>The optics' own blur in focus, µm on the sample (one standard deviation).</summary>
    public double FocusedBlurUm { get; init; } = 1.2;

    /// <summary>Blur added per µm of focus offset, µm (a cone of light: about half the objective's numerical aperture).</summary>
    public double BlurPerDefocusUm { get; init; } = 0.05;

    /// <summary>Where the camera sees sharpest, µm from the profile's visible focus (z.focusMm): what a focus sweep finds.</summary>
    public double CameraFocusOffsetUm { get; init; } = 137;

    /// <summary>How strongly the sample's grain shows, 0 (a blank mirror-polished surface) to 1.</summary>
    public double Contrast { get; init; } = 1;

    /// <summary>How dark a burn draws: the pulses' dose that halves the brightness.</summary>
    public double PulsesToHalve { get; init; } = 3;
}
