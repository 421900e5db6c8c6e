using System.ComponentModel;
using System.Globalization;
using CommunityToolkit.Mvvm.ComponentModel;
using LaserEngrave.App.Services;
using LaserEngrave.Core.Geometry;
using LaserEngrave.Core.Imaging;
using LaserEngrave.Core.Jobs;
using LaserEngrave.Core.Planning;
using LaserEngrave.Core.Vectors;

namespace LaserEngrave.App.ViewModels;

/// <summary>
/// The Image, Size and Process views: the image and its mask, the job's size and place on the stage, the process
/// values, and what follows from them (the plan, its estimate, warnings beside the fields that cause them).
/// </summary>
/// <remarks>Every change of an input re-plans at once; a change of threshold, dither or invert rebuilds the mask first.</remarks>
public sealed partial class JobViewModel : ObservableObject, IJobSession
{
    /// <summary>Field names the page places messages beside.</summary>
    public const string ImageField = "image";
    public const string WidthField = JobField.Width;
    public const string HeightField = JobField.Height;
    public const string PitchField = JobField.Pitch;
    public const string OriginField = "origin";
    public const string FrequencyField = JobField.Frequency;
    public const string BurnSpeedField = JobField.BurnSpeed;
    public const string TravelSpeedField = JobField.TravelSpeed;
    public const string AccelerationField = JobField.Acceleration;
    public const string OverscanField = JobField.Overscan;
    public const string PassesField = JobField.Passes;
    public const string ThresholdField = JobField.Threshold;
    public const string PulsesPerDotField = JobField.PulsesPerDot;
    public const string DotPitchField = JobField.DotPitch;
    public const string DotSettleField = JobField.DotSettle;
    public const string PulsesField = "pulses";
    public const string PulseEnergyField = JobField.PulseEnergy;
    public const string ToleranceField = JobField.Tolerance;
    public const string FillPitchField = JobField.FillPitch;
    public const string DrawingLayerField = "drawingLayer";

    private static readonly HashSet<string> MaskInputs = [nameof(ThresholdPercent), nameof(Dither), nameof(Invert), nameof(QuarterTurns), nameof(MirrorX), nameof(MirrorY)];

    private static readonly HashSet<string> PlanInputs =
    [
        nameof(SizeMode), nameof(WidthMm), nameof(HeightMm), nameof(PitchUm), nameof(OriginXMm), nameof(OriginYMm),
        nameof(LaserFrequencyHz), nameof(BurnSpeedMmPerS), nameof(TravelSpeedMmPerS), nameof(AccelerationMmPerS2),
        nameof(Strategy), nameof(Bidirectional), nameof(OverscanMm), nameof(Passes),
        nameof(Mode), nameof(PulsesPerDot), nameof(DotPitchMicrosteps), nameof(DotSettleMs), nameof(PulseEnergyUj),
        nameof(DrawingFill), nameof(ToleranceUm), nameof(FillPitchUm), nameof(DrawingLayer), nameof(DrawingOrder),
    ];

    private readonly IImageService _images;
    private readonly MachineActivity _activity;
    private readonly Lock _lock = new();
    /// <summary>Decoded images up to this size stay in memory for the next threshold change; larger ones are decoded again.</summary>
    public const long RetainedImageBytes = 32L << 20;

    /// <summary>The longer side of the original image's preview, px.</summary>
    public const int PreviewSidePx = 1024;

    private MachineProfile _profile;
    private LoadedImage? _image;
    private byte[]? _originalPreview;
    private int _suspended;
    private int _following;
    private CancellationTokenSource? _loading;
    private Prepared? _prepared;

    /// <param name="activity">What holds the machine: while a run, homing or a test move is under way the job cannot change.</param>
    public JobViewModel(IImageService images, MachineProfile profile, MachineActivity? activity = null)
    {
        ArgumentNullException.ThrowIfNull(images);
        ArgumentNullException.ThrowIfNull(profile);
        _images = images;
        _profile = profile;
        _activity = activity ?? new MachineActivity();
        _activity.PropertyChanged += (_, e) =>
        {
            if (e.PropertyName == nameof(MachineActivity.Current))
            {
                OnPropertyChanged(nameof(LockedBecause));
            }
        };
        Apply(FromProfile(profile));
    }

    /// <summary>Why the job cannot be changed now (a run, homing or a test move is under way); null when it can. Views disable the fields.</summary>
    public string? LockedBecause => _activity.JobLockMessage;

    [ObservableProperty]
    public partial string? ImagePath { get; private set; }

    [ObservableProperty]
    public partial ImageInfo? ImageInfo { get; private set; }

    [ObservableProperty]
    public partial BitMask? Mask { get; private set; }

    [ObservableProperty]
    public partial double ThresholdPercent { get; set; }

    [ObservableProperty]
    public partial DitherMethod Dither { get; set; }

    [ObservableProperty]
    public partial bool Invert { get; set; }

    /// <summary>Quarter turns clockwise of the image on the stage, 0..3: the mask is turned, so the plan and the burn follow it.</summary>
    [ObservableProperty]
    public partial int QuarterTurns { get; set; }

    /// <summary>The image flipped left to right (before it is turned).</summary>
    [ObservableProperty]
    public partial bool MirrorX { get; set; }

    /// <summary>The image flipped top to bottom (before it is turned).</summary>
    [ObservableProperty]
    public partial bool MirrorY { get; set; }

    /// <summary>Whether the job can be turned and mirrored: an image or a drawing (its plan is turned: VectorOptions.Orientation).</summary>
    public bool CanTurn => ImagePath is not null;

    /// <summary>The turn and mirror in force, as the Size panel says it: "upright", or e.g. "turned 90° clockwise, mirrored left to right".</summary>
    public string OrientationText
    {
        get
        {
            var parts = new List<string>();
            if (QuarterTurns != 0)
            {
                parts.Add($"turned {QuarterTurns * 90}° clockwise");
            }

            if (MirrorX)
            {
                parts.Add("image mirrored left to right");
            }

            if (MirrorY)
            {
                parts.Add("image mirrored top to bottom");
            }

            return parts.Count == 0 ? "upright" : string.Join(", ", parts);
        }
    }

    /// <summary>How the image becomes its mask now: threshold, dither, invert, turn and mirror.</summary>
    private MaskOptions MaskNow => new() { ThresholdPercent = ThresholdPercent, Dither = Dither, Invert = Invert, QuarterTurns = QuarterTurns, MirrorX = MirrorX, MirrorY = MirrorY };

    /// <summary>
    /// Turns the job a quarter turn (<paramref name="clockwise"/> or not) on the stage, keeping its size on the stage: the
    /// side that leads (width or height) takes the other side's length, so a 10 × 5 mm job becomes 5 × 10 mm.
    /// </summary>
    public void Rotate(bool clockwise)
    {
        var width = Job?.Geometry.AchievedWidthMm ?? Drawing?.Plan.WidthMm;
        var height = Job?.Geometry.AchievedHeightMm ?? Drawing?.Plan.HeightMm;
        Batch(() =>
        {
            QuarterTurns = (QuarterTurns + (clockwise ? 1 : 3)) % 4;
            switch (SizeMode)
            {
                case SizeMode.Width when height is { } h:
                    WidthMm = Math.Round(h, 6);
                    break;
                case SizeMode.Height when width is { } w:
                    HeightMm = Math.Round(w, 6);
                    break;
                case SizeMode.WidthAndHeight:
                    (WidthMm, HeightMm) = (HeightMm, WidthMm);
                    break;
            }
        });
    }

    /// <summary>Flips the job left to right on the stage, as it is turned now (a turned job's mirror is about the stage's axes).</summary>
    public void FlipHorizontal()
    {
        // Mirroring is applied before the turn: a flip about the stage's vertical axis is a flip of the image's other axis when turned an odd number of times.
        if (QuarterTurns % 2 == 0)
        {
            MirrorX = !MirrorX;
        }
        else
        {
            MirrorY = !MirrorY;
        }
    }

    /// <summary>Flips the job top to bottom on the stage, as it is turned now.</summary>
    public void FlipVertical()
    {
        if (QuarterTurns % 2 == 0)
        {
            MirrorY = !MirrorY;
        }
        else
        {
            MirrorX = !MirrorX;
        }
    }

    [ObservableProperty]
    public partial SizeMode SizeMode { get; set; }

    [ObservableProperty]
    public partial bool AspectLocked { get; set; } = true;

    [ObservableProperty]
    public partial double WidthMm { get; set; }

    [ObservableProperty]
    public partial double HeightMm { get; set; }

    [ObservableProperty]
    public partial double PitchUm { get; set; }

    [ObservableProperty]
    public partial double OriginXMm { get; set; }

    [ObservableProperty]
    public partial double OriginYMm { get; set; }

    [ObservableProperty]
    public partial double LaserFrequencyHz { get; set; }

    [ObservableProperty]
    public partial double BurnSpeedMmPerS { get; set; }

    [ObservableProperty]
    public partial double TravelSpeedMmPerS { get; set; }

    [ObservableProperty]
    public partial double AccelerationMmPerS2 { get; set; }

    [ObservableProperty]
    public partial PlanStrategy Strategy { get; set; }

    [ObservableProperty]
    public partial bool Bidirectional { get; set; }

    [ObservableProperty]
    public partial double OverscanMm { get; set; }

    [ObservableProperty]
    public partial int Passes { get; set; }

    /// <summary>Raster (burn while moving) or dots (stop at each dot and fire <see cref="PulsesPerDot"/> pulses).</summary>
    [ObservableProperty]
    public partial PlanMode Mode { get; set; }

    [ObservableProperty]
    public partial int PulsesPerDot { get; set; } = 1;

    /// <summary>Distance between dots along a run, microsteps; 0: one dot at each pixel's centre.</summary>
    [ObservableProperty]
    public partial long DotPitchMicrosteps { get; set; }

    [ObservableProperty]
    public partial double DotSettleMs { get; set; }

    /// <summary>Energy of one pulse, µJ; null: not known (no energy per pixel is shown). The job rules refuse 0 and below, as the command line does.</summary>
    [ObservableProperty]
    public partial double? PulseEnergyUj { get; set; }

    /// <summary>A drawing's paths: outlines, filled with scan lines, or both (the command line's <c>--fill</c>).</summary>
    [ObservableProperty]
    public partial VectorFillMode DrawingFill { get; set; }

    /// <summary>A drawing's chord tolerance, µm (<c>--tolerance-um</c>).</summary>
    [ObservableProperty]
    public partial double ToleranceUm { get; set; } = VectorOptions.Default.ToleranceUm;

    /// <summary>A drawing's fill pitch, µm (<c>--fill-pitch-um</c>).</summary>
    [ObservableProperty]
    public partial double FillPitchUm { get; set; } = VectorOptions.Default.FillPitchUm;

    /// <summary>Only this layer of the drawing (one of <see cref="DrawingLayers"/>), placed where it is in the whole drawing; null burns every layer.</summary>
    [ObservableProperty]
    public partial string? DrawingLayer { get; set; }

    /// <summary>Burn the paths as the drawing lists them rather than ordered (<c>--drawing-order</c>).</summary>
    [ObservableProperty]
    public partial bool DrawingOrder { get; set; }

    /// <summary>The open drawing's own layers, by name ("" for paths on none); empty for an image.</summary>
    [ObservableProperty]
    public partial IReadOnlyList<string> DrawingLayers { get; private set; } = [];

    /// <summary>The drawing's path order in one line: burn length, travel and what the order saves against the drawing's; null without a drawing.</summary>
    public string? PathOrderSummary => Drawing?.Plan is { } plan
        ? string.Create(CultureInfo.InvariantCulture, $"burn {plan.BurnLengthMm:0.###} mm · travel {plan.TravelMm:0.###} mm ({plan.TravelDrawingOrderMm:0.###} mm in drawing order, {plan.TravelSavedPercent:0.#} % saved)")
        : null;

    /// <summary>What the process does per pulse and per pixel (seed 004), in one line; null without a plan.</summary>
    public string? PulsesSummary => Job?.Pulses is { } p
        ? string.Create(CultureInfo.InvariantCulture, $"{(Mode == PlanMode.Dots ? "dots" : "pulses")} {p.PulseSpacingUm:0.###} µm apart · overlap {p.OverlapPercent:0.#} % · {p.PulsesPerPixel ?? 0:0.##} pulses per pixel{(p.EnergyPerPixelUj is { } e ? $" · {e:0.##} µJ per pixel" : string.Empty)}")
        : null;

    /// <summary>The planned job, or null without an image or with an unusable value.</summary>
    [ObservableProperty]
    public partial PreparedJob? Job { get; private set; }

    /// <summary>The planned drawing when a .dxf or .svg is open (docs/vectors.md), else null; sized by the width, or its own units.</summary>
    [ObservableProperty]
    public partial PreparedDrawing? Drawing { get; private set; }

    /// <summary>The planned image or drawing as the one job type the run, the stage and the test moves take; null without a plan.</summary>
    public EngraveJob? Engraving
    {
        get
        {
            // Made once per plan (at most one of the two is set), so whoever asks gets the same job.
            var (job, drawing) = (Job, Drawing);
            if (_engraving is { } made && ReferenceEquals(made.Job, job) && ReferenceEquals(made.Drawing, drawing))
            {
                return made.Engraving;
            }

            var engraving = drawing is not null ? EngraveJob.Of(drawing) : job is not null ? EngraveJob.Of(job) : null;
            _engraving = new MadeJob(job, drawing, engraving);
            return engraving;
        }
    }

    private MadeJob? _engraving;

    private sealed record MadeJob(PreparedJob? Job, PreparedDrawing? Drawing, EngraveJob? Engraving);

    /// <summary>Whether the open file is a drawing rather than an image.</summary>
    public bool IsDrawing => ImagePath is { } path && DrawingReader.IsDrawing(path);

    /// <summary>Estimated duration of the whole run, all passes, s: preflight, homing, the first travel and the engraving.</summary>
    [ObservableProperty]
    public partial double? EstimatedSeconds { get; private set; }

    /// <summary>Errors (which stop the plan) by field.</summary>
    [ObservableProperty]
    public partial IReadOnlyDictionary<string, string> Errors { get; private set; } = new Dictionary<string, string>();

    /// <summary>Warnings (the job can still run) by field.</summary>
    [ObservableProperty]
    public partial IReadOnlyDictionary<string, string> Warnings { get; private set; } = new Dictionary<string, string>();

    /// <summary>Goes up whenever the mask changes, so the page knows to fetch its picture again.</summary>
    [ObservableProperty]
    public partial int MaskVersion { get; private set; }

    /// <summary>Goes up whenever the plan changes, so the page redraws its cached preview.</summary>
    [ObservableProperty]
    public partial int PlanVersion { get; private set; }

    public MachineProfile Profile => _profile;

    /// <summary>
    /// Microsteps per pixel (need not be whole): the planned job's own figure, which the command line and the log give,
    /// else that of the pitch field.
    /// </summary>
    public double MicrostepsPerPixel => Job?.Geometry.MicrostepsPerPixel ?? PitchUm / _profile.X.MicrostepUm;

    /// <summary>The decoded image while it is small enough to keep (<see cref="RetainedImageBytes"/>); null for a large one, whose pixels are dropped once its mask is built.</summary>
    public LoadedImage? Image => _image;

    /// <summary>The image as a PNG of at most <see cref="PreviewSidePx"/> on its longer side, made when it was opened; null without an image.</summary>
    public byte[]? OriginalPreviewPng() => _originalPreview;

    /// <summary>The job's values as the profile suggests them.</summary>
    public static JobSettings FromProfile(MachineProfile profile)
    {
        ArgumentNullException.ThrowIfNull(profile);
        return new JobSettings
        {
            LaserFrequencyHz = profile.LaserFrequencyHz,
            BurnSpeedMmPerS = profile.BurnSpeedMmPerS,
            TravelSpeedMmPerS = profile.TravelSpeedMmPerS,
            AccelerationMmPerS2 = profile.AccelerationMmPerS2,
        };
    }

    /// <summary>Opens an image; a file that cannot be read leaves the previous image and shows the error beside the image.</summary>
    /// <remarks>An image still being opened in the background is dropped first: the later open wins, however slow the earlier.</remarks>
    /// <exception cref="MachineBusyException">A run, homing or a test move is under way.</exception>
    public bool LoadImage(string path) => LoadImage(path, upright: true);

    private bool LoadImage(string path, bool upright)
    {
        ArgumentException.ThrowIfNullOrWhiteSpace(path);
        _activity.ThrowIfJobLocked();
        CancelLoad();
        upright &= path != ImagePath;
        if (DrawingReader.IsDrawing(path))
        {
            return OpenDrawing(path, upright);
        }

        if (!Open(path))
        {
            return false;
        }

        if (upright)
        {
            Upright();
        }

        RebuildMask();
        return true;
    }

    /// <summary>
    /// Another file opens upright, as LightBurn opens one: the last job's turn and mirrors were that artwork's (a job put
    /// back, from the history or the last session, sets its own afterwards). Only once the file has opened: one that
    /// cannot be read leaves the open job as it was, turn and all.
    /// </summary>
    private void Upright()
    {
        Interlocked.Increment(ref _suspended);
        try
        {
            QuarterTurns = 0;
            MirrorX = false;
            MirrorY = false;
        }
        finally
        {
            Interlocked.Decrement(ref _suspended);
        }
    }

    /// <summary>
    /// Opens an image off the caller's path: reads it, makes its mask and plans it on the thread pool, saying which in
    /// <see cref="LoadingLine"/>. The job shown stays the last good one (its name, size and estimate) until the new one
    /// is ready; <see cref="CancelLoad"/> or a later open drops it and keeps that job. A drawing opens at once, as in
    /// <see cref="LoadImage"/>.
    /// </summary>
    /// <returns>True when the image opened; false when it did not (why stands beside the image) or the open was cancelled.</returns>
    /// <exception cref="MachineBusyException">A run, homing or a test move is under way.</exception>
    /// <param name="upright">Whether another file opens upright (<see cref="Upright"/>); false: with the turn in force (the last session's job put back).</param>
    public async Task<bool> LoadImageAsync(string path, CancellationToken cancellationToken = default, bool upright = true)
    {
        ArgumentException.ThrowIfNullOrWhiteSpace(path);
        _activity.ThrowIfJobLocked();
        if (DrawingReader.IsDrawing(path))
        {
            return LoadImage(path, upright);
        }

        CancelLoad();
        using var loading = CancellationTokenSource.CreateLinkedTokenSource(cancellationToken);
        _loading = loading;
        var name = Path.GetFileName(path);
        upright &= path != ImagePath;
        var spec = Spec(path);
        if (upright)
        {
            spec = spec with { Mask = spec.Mask with { QuarterTurns = 0, MirrorX = false, MirrorY = false } };
        }

        var progress = new Progress<string>(line =>
        {
            if (ReferenceEquals(Volatile.Read(ref _loading), loading))
            {
                LoadingLine = line;
            }
        });
        LoadingLine = $"Reading {name}…";
        Opened opened;
        try
        {
            var work = Task.Run(() => Decode(spec, name, progress, loading.Token), loading.Token);
            opened = await work.WaitAsync(loading.Token).ConfigureAwait(true);
        }
        catch (OperationCanceledException)
        {
            return false;
        }
        catch (ImageLoadException ex)
        {
            SetErrors(new Dictionary<string, string>(Errors) { [ImageField] = ex.Message });
            return false;
        }
        catch (Exception ex) when (ex is IOException or UnauthorizedAccessException or ArgumentException)
        {
            SetErrors(new Dictionary<string, string>(Errors) { [ImageField] = $"{path}: {ex.Message}" });
            return false;
        }
        finally
        {
            if (ReferenceEquals(Interlocked.CompareExchange(ref _loading, null, loading), loading))
            {
                LoadingLine = null;
            }
        }

        if (loading.IsCancellationRequested)
        {
            // Dropped after its work had ended: a later open (or Cancel) came first and keeps its job.
            return false;
        }

        if (LockedBecause is { } locked)
        {
            // A run or a move began while the image was read: the job it holds stays.
            SetErrors(new Dictionary<string, string>(Errors) { [ImageField] = $"{name} was not opened: {locked}" });
            return false;
        }

        lock (_lock)
        {
            if (upright)
            {
                Upright();
            }

            _image = opened.Image;
            _originalPreview = opened.Preview;
            ImagePath = path;
            ImageInfo = opened.Info;
            DrawingLayers = [];
            Mask = opened.Mask;
            MaskVersion++;
            var errors = new Dictionary<string, string>(Errors);
            errors.Remove(ImageField);
            errors.Remove(ThresholdField);
            if (opened.MaskError is { } maskError)
            {
                errors[ThresholdField] = maskError;
            }

            SetErrors(errors);
            _prepared = opened.Job;
        }

        OnPropertyChanged(nameof(IsDrawing));
        if (opened.MaskOptions != MaskNow)
        {
            // The threshold, dither or invert changed while the image was read: its mask is made again as they say now.
            RebuildMask();
        }
        else
        {
            Replan();
        }

        return true;
    }

    /// <summary>Stops an image being opened by <see cref="LoadImageAsync"/>; the job shown stays. Nothing happens when none is.</summary>
    public void CancelLoad()
    {
        if (Interlocked.Exchange(ref _loading, null) is { } loading)
        {
            loading.Cancel();
            LoadingLine = null;
        }
    }

    /// <summary>What an image being opened in the background is doing now ("Reading big.png…"); null when none is.</summary>
    [ObservableProperty]
    public partial string? LoadingLine { get; private set; }

    /// <summary>The heavy part of opening an image, on the thread pool: decode, preview, mask and plan, checking for a cancel between them.</summary>
    private Opened Decode(JobSpec spec, string name, IProgress<string> progress, CancellationToken cancellationToken)
    {
        var image = _images.Load(spec.ImagePath);
        cancellationToken.ThrowIfCancellationRequested();
        var preview = _images.RenderOriginalPng(image, PreviewSidePx);
        cancellationToken.ThrowIfCancellationRequested();
        progress.Report($"Making the mask of {name}…");
        BitMask? mask = null;
        string? maskError = null;
        try
        {
            mask = _images.BuildMask(image, spec.Mask);
        }
        catch (Exception ex) when (ex is ArgumentException or InvalidOperationException)
        {
            maskError = ex.Message;
        }

        cancellationToken.ThrowIfCancellationRequested();
        Prepared? job = null;
        if (mask is not null)
        {
            progress.Report($"Planning {name}…");
            spec = spec with { ImagePath = image.Info.Path };
            try
            {
                job = new Prepared(spec, mask, _images.Prepare(spec, image.Info, mask));
            }
            catch (Exception ex) when (ex is GeometryException or PlanException)
            {
                // The plan made on the page's path says why, beside the field to change.
            }
        }

        cancellationToken.ThrowIfCancellationRequested();

        // Only the 1-bit mask stays of a large image, as after a mask is built (see RetainedImageBytes).
        var kept = (long)image.Stride * image.Height > RetainedImageBytes ? null : image;
        return new Opened(kept, image.Info, preview, spec.Mask, mask, maskError, job);
    }

    /// <summary>An image read, masked and planned in the background, ready to become the job.</summary>
    private sealed record Opened(LoadedImage? Image, ImageInfo Info, byte[] Preview, MaskOptions MaskOptions, BitMask? Mask, string? MaskError, Prepared? Job);

    /// <summary>A plan made in the background, used by the next plan only when its spec and mask are still the job's.</summary>
    private sealed record Prepared(JobSpec Spec, BitMask Mask, PreparedJob Job);

    /// <summary>
    /// An upload that did not open: its error names the file as the user chose it, not the app's copy of it in
    /// images/ (which is removed again).
    /// </summary>
    public void NameUploadInError(string copyPath, string userFileName)
    {
        if (Errors.TryGetValue(ImageField, out var error) && error.Contains(copyPath, StringComparison.Ordinal))
        {
            SetErrors(new Dictionary<string, string>(Errors) { [ImageField] = error.Replace(copyPath, userFileName, StringComparison.Ordinal) });
        }
    }

    /// <summary>A drawing has no pixels: the image and mask go, and the plan reads it (its errors stand beside the image).</summary>
    private bool OpenDrawing(string path, bool upright)
    {
        IReadOnlyList<string> layers;
        try
        {
            // Read once first: a drawing that cannot be read leaves the open image or drawing as it was.
            layers = DrawingReader.Read(path).Layers();
        }
        catch (DrawingException ex)
        {
            SetErrors(new Dictionary<string, string>(Errors) { [ImageField] = ex.Message });
            return false;
        }
        catch (Exception ex) when (ex is IOException or UnauthorizedAccessException)
        {
            SetErrors(new Dictionary<string, string>(Errors) { [ImageField] = $"{path}: {ex.Message}" });
            return false;
        }

        lock (_lock)
        {
            if (upright)
            {
                Upright();
            }

            _image = null;
            _originalPreview = null;
            ImageInfo = null;
            Mask = null;
            MaskVersion++;
            ImagePath = path;
            DrawingLayers = layers;
            if (DrawingLayer is { } chosen && !layers.Contains(chosen, StringComparer.Ordinal))
            {
                Interlocked.Increment(ref _suspended);
                try
                {
                    DrawingLayer = null;
                }
                finally
                {
                    Interlocked.Decrement(ref _suspended);
                }
            }

            var errors = new Dictionary<string, string>(Errors);
            errors.Remove(ImageField);
            errors.Remove(ThresholdField);
            SetErrors(errors);
        }

        OnPropertyChanged(nameof(IsDrawing));
        Replan();
        if (Errors.ContainsKey(ImageField))
        {
            return false;
        }

        return true;
    }

    /// <summary>Decodes the image and its preview into the fields; a method of its own so no caller's frame keeps the pixels alive.</summary>
    private bool Open(string path)
    {
        LoadedImage image;
        try
        {
            image = _images.Load(path);
        }
        catch (ImageLoadException ex)
        {
            SetErrors(new Dictionary<string, string>(Errors) { [ImageField] = ex.Message });
            return false;
        }
        catch (Exception ex) when (ex is IOException or UnauthorizedAccessException)
        {
            SetErrors(new Dictionary<string, string>(Errors) { [ImageField] = $"{path}: {ex.Message}" });
            return false;
        }

        byte[] preview;
        try
        {
            preview = _images.RenderOriginalPng(image, PreviewSidePx);
        }
        catch (ArgumentException ex)
        {
            SetErrors(new Dictionary<string, string>(Errors) { [ImageField] = $"{path}: {ex.Message}" });
            return false;
        }

        lock (_lock)
        {
            _image = image;
            _originalPreview = preview;
            ImagePath = path;
            ImageInfo = image.Info;
            DrawingLayers = [];
        }

        return true;
    }

    /// <summary>The user typed a width: with the aspect locked the height follows; unlocked, both sides are kept.</summary>
    public void EditWidth(double widthMm) => Batch(() =>
    {
        WidthMm = widthMm;
        SizeMode = AspectLocked ? SizeMode.Width : SizeMode.WidthAndHeight;
    });

    public void EditHeight(double heightMm) => Batch(() =>
    {
        HeightMm = heightMm;
        SizeMode = AspectLocked ? SizeMode.Height : SizeMode.WidthAndHeight;
    });

    public void EditPitch(double pitchUm) => Batch(() =>
    {
        PitchUm = pitchUm;
        SizeMode = SizeMode.Pitch;
    });

    public void EditMicrostepsPerPixel(double microsteps) => EditPitch(microsteps * _profile.X.MicrostepUm);

    /// <summary>
    /// The job dropped on the stage at (<paramref name="xMm"/>, <paramref name="yMm"/>), snapped to 0.01 mm: placed as the
    /// same origin typed would be, and refused with the same sentence (the origin goes back) where the job rules refuse
    /// the typed origin. Returns that sentence, or null when it was placed.
    /// </summary>
    public string? PlaceAt(double xMm, double yMm)
    {
        if (LockedBecause is { } locked)
        {
            return locked;
        }

        if (ImagePath is null)
        {
            return "no job to place";
        }

        var (x, y) = (Math.Round(xMm, 2), Math.Round(yMm, 2));
        var (oldX, oldY) = (OriginXMm, OriginYMm);
        try
        {
            Batch(() => (OriginXMm, OriginYMm) = (x, y));
            if (Errors.TryGetValue(OriginField, out var refused))
            {
                Batch(() => (OriginXMm, OriginYMm) = (oldX, oldY));
                return $"not placed at {N(x)}, {N(y)} mm: {refused}";
            }
        }
        catch (MachineBusyException ex)
        {
            // The lock came between the check and the drop.
            return ex.Message;
        }

        return null;
    }

    /// <summary>Throws <see cref="MachineBusyException"/> while an operation fixes the job (an upload asks before it is kept).</summary>
    public void ThrowIfLocked() => _activity.ThrowIfJobLocked();

    /// <summary>Uses another machine profile (its travel and microstep) for the plan.</summary>
    public void UseProfile(MachineProfile profile)
    {
        ArgumentNullException.ThrowIfNull(profile);
        _activity.ThrowIfJobLocked();
        _profile = profile;
        OnPropertyChanged(nameof(Profile));
        Replan();
    }

    /// <summary>Sets every value at once (a history entry loaded again), then plans once.</summary>
    public void Apply(JobSettings settings)
    {
        ArgumentNullException.ThrowIfNull(settings);
        Batch(() =>
        {
            Assign(settings);
            AspectLocked = settings.SizeMode != SizeMode.WidthAndHeight;
        });
        if (settings.ImagePath is { } path && path != ImagePath)
        {
            // The job put back keeps its own turn and mirrors, set above.
            LoadImage(path, upright: false);
        }
    }

    /// <inheritdoc/>
    public void Change(Func<JobSettings, JobSettings> change)
    {
        ArgumentNullException.ThrowIfNull(change);
        var changed = change(ToSettings());
        Batch(() => Assign(changed));
    }

    /// <summary>Every field from <paramref name="settings"/> (a value that stays raises nothing), without the file.</summary>
    private void Assign(JobSettings settings)
    {
        ThresholdPercent = settings.ThresholdPercent;
        Dither = settings.Dither;
        Invert = settings.Invert;
        QuarterTurns = settings.QuarterTurns;
        MirrorX = settings.MirrorX;
        MirrorY = settings.MirrorY;
        SizeMode = settings.SizeMode;
        WidthMm = settings.WidthMm;
        HeightMm = settings.HeightMm;
        PitchUm = settings.PitchUm;
        OriginXMm = settings.OriginXMm;
        OriginYMm = settings.OriginYMm;
        LaserFrequencyHz = settings.LaserFrequencyHz;
        BurnSpeedMmPerS = settings.BurnSpeedMmPerS;
        TravelSpeedMmPerS = settings.TravelSpeedMmPerS;
        AccelerationMmPerS2 = settings.AccelerationMmPerS2;
        Strategy = settings.Strategy;
        Bidirectional = settings.Bidirectional;
        OverscanMm = settings.OverscanMm;
        Passes = settings.Passes;
        Mode = settings.Mode;
        PulsesPerDot = settings.PulsesPerDot;
        DotPitchMicrosteps = settings.DotPitchMicrosteps;
        DotSettleMs = settings.DotSettleMs;
        PulseEnergyUj = settings.PulseEnergyUj;
        DrawingFill = settings.DrawingFill;
        ToleranceUm = settings.ToleranceUm;
        FillPitchUm = settings.FillPitchUm;
        DrawingLayer = settings.DrawingLayer;
        DrawingOrder = settings.DrawingOrder;
    }

    public JobSettings ToSettings() => new()
    {
        ImagePath = ImagePath,
        ThresholdPercent = ThresholdPercent,
        Dither = Dither,
        Invert = Invert,
        QuarterTurns = QuarterTurns,
        MirrorX = MirrorX,
        MirrorY = MirrorY,
        SizeMode = SizeMode,
        WidthMm = WidthMm,
        HeightMm = HeightMm,
        PitchUm = PitchUm,
        OriginXMm = OriginXMm,
        OriginYMm = OriginYMm,
        LaserFrequencyHz = LaserFrequencyHz,
        BurnSpeedMmPerS = BurnSpeedMmPerS,
        TravelSpeedMmPerS = TravelSpeedMmPerS,
        AccelerationMmPerS2 = AccelerationMmPerS2,
        Strategy = Strategy,
        Bidirectional = Bidirectional,
        OverscanMm = OverscanMm,
        Passes = Passes,
        Mode = Mode,
        PulsesPerDot = PulsesPerDot,
        DotPitchMicrosteps = DotPitchMicrosteps,
        DotSettleMs = DotSettleMs,
        PulseEnergyUj = PulseEnergyUj,
        DrawingFill = DrawingFill,
        ToleranceUm = ToleranceUm,
        FillPitchUm = FillPitchUm,
        DrawingLayer = DrawingLayer,
        DrawingOrder = DrawingOrder,
    };

    /// <summary>Runs several changes and plans once at the end.</summary>
    /// <exception cref="MachineBusyException">A run, homing or a test move is under way: nothing is changed.</exception>
    public void Batch(Action changes)
    {
        ArgumentNullException.ThrowIfNull(changes);
        _activity.ThrowIfJobLocked();
        Interlocked.Increment(ref _suspended);
        var maskChanged = false;
        var planChanged = false;
        void Watch(object? sender, PropertyChangedEventArgs e)
        {
            maskChanged |= MaskInputs.Contains(e.PropertyName!);
            planChanged |= PlanInputs.Contains(e.PropertyName!);
        }

        PropertyChanged += Watch;
        try
        {
            changes();
        }
        finally
        {
            PropertyChanged -= Watch;
            Interlocked.Decrement(ref _suspended);
        }

        if (maskChanged)
        {
            RebuildMask();
        }
        else if (planChanged)
        {
            Replan();
        }
    }

    /// <summary>Every job value refuses to change while the machine works on the job: the one place the interlock is kept.</summary>
    protected override void OnPropertyChanging(PropertyChangingEventArgs e)
    {
        ArgumentNullException.ThrowIfNull(e);
        if (Volatile.Read(ref _following) == 0 && (MaskInputs.Contains(e.PropertyName!) || PlanInputs.Contains(e.PropertyName!) || e.PropertyName == nameof(AspectLocked)))
        {
            _activity.ThrowIfJobLocked();
        }

        base.OnPropertyChanging(e);
    }

    protected override void OnPropertyChanged(PropertyChangedEventArgs e)
    {
        ArgumentNullException.ThrowIfNull(e);
        base.OnPropertyChanged(e);
        if (Volatile.Read(ref _suspended) > 0)
        {
            return;
        }

        if (MaskInputs.Contains(e.PropertyName!))
        {
            RebuildMask();
        }
        else if (PlanInputs.Contains(e.PropertyName!))
        {
            Replan();
        }
    }

    private void RebuildMask()
    {
        // A drawing has no mask: its turn and mirrors are its plan's.
        if (BuildMask() || IsDrawing)
        {
            Replan();
        }
    }

    /// <summary>Builds the mask; false without an image.</summary>
    /// <remarks>
    /// A method of its own, so no caller's frame keeps a large image's pixels alive: once dropped here they are the
    /// garbage collector's to take back when it needs to (the app forces no collection; RunMemoryTests watches the heap).
    /// </remarks>
    private bool BuildMask()
    {
        lock (_lock)
        {
            if (ImagePath is not { } path || ImageInfo is null)
            {
                return false;
            }

            var errors = new Dictionary<string, string>(Errors);
            errors.Remove(ImageField);
            errors.Remove(ThresholdField);
            try
            {
                // A large image was dropped after its last mask: decode it again (its file is the app's copy or the user's own).
                var image = _image ?? _images.Load(path);
                Mask = _images.BuildMask(image, MaskNow);
                MaskVersion++;
                if ((long)image.Stride * image.Height > RetainedImageBytes)
                {
                    // Only the 1-bit mask stays: a 32768 x 32768 greyscale image would otherwise keep 1 GB.
                    _image = null;
                }
            }
            catch (ImageLoadException ex)
            {
                errors[ImageField] = ex.Message;
                Mask = null;
            }
            catch (Exception ex) when (ex is ArgumentException or InvalidOperationException)
            {
                errors[ThresholdField] = ex.Message;
                Mask = null;
            }

            SetErrors(errors);
        }

        return true;
    }

    private void Replan()
    {
        lock (_lock)
        {
            var errors = JobPlanner.FieldErrors(ToSettings(), _profile);
            JobPlan plan;
            if (IsDrawing)
            {
                plan = JobPlanner.Drawing(Spec(ImagePath!), SizeMode, WidthMm, DrawingOptions(), errors);
            }
            else
            {
                foreach (var key in new[] { ImageField, ThresholdField })
                {
                    if (Errors.TryGetValue(key, out var message))
                    {
                        errors[key] = message;
                    }
                }

                // A plan made while the image was opened serves once; it is not kept beside the job.
                var prepared = _prepared;
                _prepared = null;
                plan = JobPlanner.Image(Spec(ImageInfo?.Path ?? string.Empty), SizeMode, Mask, ImageInfo, errors, (spec, info, mask) =>
                    prepared is { } ready && ReferenceEquals(ready.Mask, mask) && ready.Spec == spec ? ready.Job : _images.Prepare(spec, info, mask));
            }

            Follow(plan);
            Job = plan.Job;
            Drawing = plan.Drawing;
            EstimatedSeconds = plan.Job?.Statistics.WholeRunSeconds(Passes) ?? plan.Drawing?.WholeRunSeconds(Passes);
            SetErrors(plan.Errors);
            Warnings = plan.Warnings;
            OnPropertyChanged(nameof(MicrostepsPerPixel));
            OnPropertyChanged(nameof(PulsesSummary));
            OnPropertyChanged(nameof(PathOrderSummary));
            PlanVersion++;
        }
    }

    /// <summary>The fields that follow the plan show what the job will really be, without planning again.</summary>
    private void Follow(JobPlan plan)
    {
        Interlocked.Increment(ref _suspended);
        Interlocked.Increment(ref _following);
        try
        {
            WidthMm = plan.WidthMm ?? WidthMm;
            HeightMm = plan.HeightMm ?? HeightMm;
            PitchUm = plan.PitchUm ?? PitchUm;
        }
        finally
        {
            Interlocked.Decrement(ref _following);
            Interlocked.Decrement(ref _suspended);
        }
    }

    private JobSpec Spec(string path) => new()
    {
        ImagePath = path,
        Mask = MaskNow,
        Size = SizeMode switch
        {
            SizeMode.Height => SizeSpec.Height(HeightMm),
            SizeMode.WidthAndHeight => SizeSpec.WidthAndHeight(WidthMm, HeightMm),
            SizeMode.Pitch => SizeSpec.Pitch(PitchUm),
            _ => SizeSpec.Width(WidthMm),
        },
        Origin = new OriginMm(OriginXMm, OriginYMm),
        Plan = PlanOptions(),
        Passes = Passes,
        Process = Process(),
        Profile = _profile,
    };

    /// <summary>The process values as the fields say them (a sweep's base process).</summary>
    public ProcessSettings Process() => ProcessSettings.FromProfile(_profile) with
    {
        LaserFrequencyHz = LaserFrequencyHz,
        BurnSpeedMmPerS = BurnSpeedMmPerS,
        TravelSpeedMmPerS = TravelSpeedMmPerS,
        AccelerationMmPerS2 = AccelerationMmPerS2,
        PulseEnergyUj = PulseEnergyUj,
        Mode = Mode,
        PulsesPerDot = Mode == PlanMode.Dots ? PulsesPerDot : 1,
        DotPitchMicrosteps = Mode == PlanMode.Dots ? DotPitchMicrosteps : 0,
        DotSettleMs = Mode == PlanMode.Dots ? DotSettleMs : 0,
    };

    /// <summary>A drawing's options as the fields say them: the same <see cref="VectorOptions"/> the command line binds.</summary>
    public VectorOptions DrawingOptions() => new()
    {
        ToleranceUm = ToleranceUm,
        Fill = DrawingFill,
        FillPitchUm = FillPitchUm,
        Layer = DrawingLayer,
        Optimize = !DrawingOrder,
    };

    /// <summary>The plan options as the fields say them.</summary>
    public PlanOptions PlanOptions() => new() { Strategy = Strategy, Bidirectional = Bidirectional, OverscanMm = OverscanMm };

    private void SetErrors(Dictionary<string, string> errors) => Errors = errors;

    private static string N(double value) => value.ToString("0.######", CultureInfo.InvariantCulture);
}
