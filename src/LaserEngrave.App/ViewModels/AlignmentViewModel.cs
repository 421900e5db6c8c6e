using System.Globalization;
using CommunityToolkit.Mvvm.ComponentModel;
using CommunityToolkit.Mvvm.Input;
using LaserEngrave.App.Services;
using LaserEngrave.Core.Alignment;
using LaserEngrave.Core.Geometry;
using LaserEngrave.Core.Imaging;

namespace LaserEngrave.App.ViewModels;

/// <summary>
/// The Alignment view, the command line's <c>align</c>: two fiducial marks, each where it is in the job and where the
/// stage found it (jog the laser onto it, then take the stage's position), and the job rotated and moved onto them.
/// </summary>
/// <remarks>
/// The job's mask is resampled into stage coordinates (rows stay along X: docs/alignment.md), written into the app's data
/// folder and opened as the job at the same pitch, at the aligned origin.
/// </remarks>
public sealed partial class AlignmentViewModel : ObservableObject
{
    private readonly MainViewModel _main;
    private readonly string _dataFolder;

    public AlignmentViewModel(MainViewModel main, string dataFolder)
    {
        ArgumentNullException.ThrowIfNull(main);
        ArgumentException.ThrowIfNullOrWhiteSpace(dataFolder);
        _main = main;
        _dataFolder = dataFolder;
    }

    /// <summary>Mark 1's position in the job, mm from its top-left corner.</summary>
    [ObservableProperty]
    public partial double Job1XMm { get; set; }

    [ObservableProperty]
    public partial double Job1YMm { get; set; }

    /// <summary>Where the stage found mark 1, mm.</summary>
    [ObservableProperty]
    public partial double Stage1XMm { get; set; }

    [ObservableProperty]
    public partial double Stage1YMm { get; set; }

    [ObservableProperty]
    public partial double Job2XMm { get; set; }

    [ObservableProperty]
    public partial double Job2YMm { get; set; }

    [ObservableProperty]
    public partial double Stage2XMm { get; set; }

    [ObservableProperty]
    public partial double Stage2YMm { get; set; }

    /// <summary>What the last alignment did: rotation, distance check, new origin.</summary>
    [ObservableProperty]
    public partial IReadOnlyList<string> ResultLines { get; private set; } = [];

    [ObservableProperty]
    public partial string? Error { get; private set; }

    /// <summary>Takes the stage's position (where the laser was jogged onto the mark) as mark 1's or mark 2's.</summary>
    [RelayCommand]
    private void TakeStagePosition(int mark)
    {
        var machine = _main.Machine;
        if (machine.XMicrosteps is not { } x || machine.YMicrosteps is not { } y)
        {
            Error = "the stage's position is not known: connect, home and jog onto the mark first";
            return;
        }

        var xMm = StageUnits.MicrostepsToMm(x, machine.Profile.X.MicrostepUm);
        var yMm = StageUnits.MicrostepsToMm(y, machine.Profile.Y.MicrostepUm);
        if (mark == 1)
        {
            (Stage1XMm, Stage1YMm) = (xMm, yMm);
        }
        else
        {
            (Stage2XMm, Stage2YMm) = (xMm, yMm);
        }

        Error = null;
    }

    /// <summary>Rotates and moves the job onto the two marks and opens the aligned job.</summary>
    [RelayCommand]
    private void Align()
    {
        var job = _main.Job;
        if (job.Mask is not { } mask || job.Job is not { } prepared)
        {
            Error = "open and size the job first: the marks are given in its millimetres";
            return;
        }

        try
        {
            var profile = job.Profile;
            var alignment = FiducialAlignment.Solve(
                new Fiducial(Job1XMm, Job1YMm, Stage1XMm, Stage1YMm),
                new Fiducial(Job2XMm, Job2YMm, Stage2XMm, Stage2YMm),
                FiducialAlignment.DefaultToleranceUm,
                profile.Calibration);
            var pitchUm = prepared.Geometry.PitchUm;
            var aligned = MaskResampler.Resample(mask, pitchUm, alignment.Transform, profile.Calibration);
            var folder = Path.Combine(_dataFolder, "images");
            Directory.CreateDirectory(folder);
            var name = Path.GetFileNameWithoutExtension(job.ImagePath ?? "job");
            var path = Path.Combine(folder, $"{name}-aligned.png");
            PngWriter.WriteMask(path, aligned.Mask);

            // The aligned mask is black = burn already, and already turned and mirrored: threshold it as it is.
            job.Batch(() =>
            {
                job.Invert = false;
                job.Dither = DitherMethod.None;
                job.ThresholdPercent = 50;
                job.QuarterTurns = 0;
                job.MirrorX = false;
                job.MirrorY = false;
            });
            if (job.LoadImage(path))
            {
                job.Batch(() =>
                {
                    job.EditPitch(pitchUm);
                    job.OriginXMm = aligned.OriginXMm;
                    job.OriginYMm = aligned.OriginYMm;
                });
            }

            var c = CultureInfo.InvariantCulture;
            ResultLines =
            [
                string.Create(c, $"Rotation: {alignment.Transform.AngleDegrees:+0.####;-0.####;0}° (+x turned towards +y)"),
                string.Create(c, $"Distance check: {alignment.DistanceMismatchUm:+0.#;-0.#;0} µm between the marks ({alignment.ScaleMismatchPpm:+0;-0;0} ppm)"),
                string.Create(c, $"Aligned job: {aligned.Mask.Width} × {aligned.Mask.Height} px at {pitchUm:0.####} µm, origin {aligned.OriginXMm:0.####}, {aligned.OriginYMm:0.####} mm"),
            ];
            Error = null;
        }
        catch (Exception ex) when (ex is AlignmentException or IOException or UnauthorizedAccessException or MachineBusyException)
        {
            Error = ex.Message;
        }
    }
}
