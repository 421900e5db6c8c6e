using CommunityToolkit.Mvvm.ComponentModel;
using LaserEngrave.App.Services;
using LaserEngrave.Core.Geometry;
using LaserEngrave.Core.Jobs;
using LaserEngrave.Core.Planning;
using LaserEngrave.Core.Vectors;

namespace LaserEngrave.App.ViewModels;

/// <summary>
/// The Layers view: a job of layers (images and drawings, each with its own mode, origin, speed, frequency and passes),
/// opened from a job file or built from the open image or drawing, planned as <c>engrave --job</c> plans it, and saved
/// in the same JSON. While it has layers, Start runs them (one <c>EngraveSession</c>) rather than the single job.
/// </summary>
public sealed partial class LayersViewModel : ObservableObject
{
    private readonly IJobFiles _files;
    /// <summary>The most a job file chosen in the browser may weigh: a thousand layers of JSON are far below it.</summary>
    public const long MaxJobFileBytes = 16L << 20;

    private readonly IJobSession _job;
    private readonly MachineActivity _activity;
    private IReadOnlyList<JobLayer>? _inFile;

    // Set while a job file of one layer is put into the single job: that image is the file's, not another.
    private bool _openingSingle;

    public LayersViewModel(IJobFiles files, IJobSession job, MachineActivity activity)
    {
        ArgumentNullException.ThrowIfNull(files);
        ArgumentNullException.ThrowIfNull(job);
        ArgumentNullException.ThrowIfNull(activity);
        _files = files;
        _job = job;
        _activity = activity;
        SampleJobs = files.SampleJobs();
        _job.PropertyChanged += (_, e) =>
        {
            if (e.PropertyName == nameof(IJobSession.Profile) && IsActive)
            {
                Replan();
            }

            if (e.PropertyName == nameof(IJobSession.ImagePath) && !IsActive && !_openingSingle)
            {
                // Another image or drawing is not the job file opened or saved: Save must not write over that file.
                JobPath = null;
            }

            if (e.PropertyName is nameof(IJobSession.PlanVersion) or nameof(IJobSession.ImagePath))
            {
                OnPropertyChanged(nameof(CanSave));
                OnPropertyChanged(nameof(SuggestedPath));
            }
        };
        _activity.PropertyChanged += (_, e) =>
        {
            if (e.PropertyName == nameof(MachineActivity.Current))
            {
                OnPropertyChanged(nameof(LockedBecause));
            }
        };
    }

    /// <summary>The job files shipped with the app.</summary>
    public IReadOnlyList<string> SampleJobs { get; }

    /// <summary>Why the layers cannot change now (a run, homing or a test move); null when they can.</summary>
    public string? LockedBecause => _activity.JobLockMessage;

    /// <summary>The layers in burn order.</summary>
    [ObservableProperty]
    [NotifyPropertyChangedFor(nameof(IsActive))]
    [NotifyPropertyChangedFor(nameof(CanSave))]
    public partial IReadOnlyList<JobLayer> Layers { get; private set; } = [];

    /// <summary>The layers planned, or null when there are none or one cannot be planned (<see cref="Error"/> says why).</summary>
    [ObservableProperty]
    [NotifyPropertyChangedFor(nameof(EstimatedSeconds))]
    public partial LayeredJob? Job { get; private set; }

    /// <summary>The layers planned as the one job type the run takes; null when <see cref="Job"/> is.</summary>
    public EngraveJob? Engraving { get; private set; }

    // Made once per plan, so whoever asks (Start's rule, the stage) gets the same job.
    partial void OnJobChanged(LayeredJob? value) => Engraving = value is null ? null : EngraveJob.Of(value);

    /// <summary>Why the layers cannot be planned or run, one line naming the layer and the value; null when they can.</summary>
    [ObservableProperty]
    public partial string? Error { get; private set; }

    /// <summary>The layer (from 0) <see cref="Error"/> is about, so the view shows it there; null when it is about none.</summary>
    [ObservableProperty]
    public partial int? ErrorLayer { get; private set; }

    /// <summary>Why the last open or save did nothing, one line; null after one that worked.</summary>
    [ObservableProperty]
    public partial string? FileError { get; private set; }

    /// <summary>The job file last opened or saved; the Save field offers it.</summary>
    [ObservableProperty]
    public partial string? JobPath { get; private set; }

    /// <summary>Goes up whenever the layers' plan changes, so the stage canvas draws them again.</summary>
    [ObservableProperty]
    public partial int PlanVersion { get; private set; }

    /// <summary>
    /// The job file the layers are, unchanged since it was opened or saved: a run logs it (with its SHA-256), so the
    /// command line can resume the run (<c>engrave --from-log LOG --resume</c>); null once a layer changed.
    /// </summary>
    public string? UnchangedJobFile => JobPath is { } path && _inFile is { } saved && saved.SequenceEqual(Layers) ? path : null;

    /// <summary>Whether there are layers: then Start runs them, not the single job.</summary>
    public bool IsActive => Layers.Count > 0;

    /// <summary>The whole job: every layer's passes with their preflight, s; null without a plan.</summary>
    public double? EstimatedSeconds => Job?.EstimatedSeconds;

    /// <summary>
    /// Where a new job file would be saved: the last one, else in the app's jobs folder job.json (layers) or the single
    /// job's image or drawing name with .json.
    /// </summary>
    public string SuggestedPath => JobPath ?? Path.Combine(_files.DefaultFolder, DownloadName);

    /// <summary>The name a job file downloaded by the page is offered under: the last one's, else as <see cref="SuggestedPath"/>.</summary>
    public string DownloadName => JobPath is { } path
        ? Path.GetFileName(path)
        : (!IsActive && _job.ImagePath is { } image ? Path.GetFileNameWithoutExtension(image) : "job") + ".json";

    /// <summary>Whether there is a job to save: layers, or an open image or drawing that plans.</summary>
    public bool CanSave => IsActive || (_job.ImagePath is not null && _job.Engraving is not null);

    /// <summary>
    /// The layers a job file of the job now holds: the layers, or, when there are none, the open image or drawing as one
    /// layer with the values its fields have (opened back, it is the single job again); null with <paramref name="problem"/>
    /// saying why when there is nothing to save.
    /// </summary>
    public IReadOnlyList<JobLayer>? ToSave(out string? problem)
    {
        if (IsActive)
        {
            problem = null;
            return Layers;
        }

        return CurrentAsLayer(out problem) is { } layer ? [layer] : null;
    }

    /// <summary>
    /// The job file's bytes for the page to download (sources as full paths: the file's folder is the browser's); null
    /// with <see cref="FileError"/> saying why when there is nothing to save.
    /// </summary>
    public byte[]? ToDownload()
    {
        if (ToSave(out var problem) is not { } layers)
        {
            FileError = problem;
            return null;
        }

        FileError = null;
        return JobFile.ToJson(layers, null);
    }

    /// <summary>Adds the open image or drawing, with the values its fields have now, as the last layer.</summary>
    /// <returns>False (with <see cref="FileError"/> saying why) when nothing is open or its values do not plan.</returns>
    public bool AddCurrent()
    {
        _activity.ThrowIfJobLocked();
        if (CurrentAsLayer(out var problem) is not { } layer)
        {
            FileError = problem + " before adding it as a layer";
            return false;
        }

        FileError = null;
        Set([.. Layers, layer with { Name = UniqueName(layer.Name) }]);
        return true;
    }

    /// <summary>Rows of an array (<see cref="AddArray"/>): the copies down the stage.</summary>
    [ObservableProperty]
    public partial int ArrayRows { get; set; } = 2;

    /// <summary>Columns of an array: the copies across the stage.</summary>
    [ObservableProperty]
    public partial int ArrayColumns { get; set; } = 2;

    /// <summary>The distance from one copy's origin to the next across, mm.</summary>
    [ObservableProperty]
    public partial double ArrayPitchXMm { get; set; } = 10;

    /// <summary>The distance from one copy's origin to the next down, mm.</summary>
    [ObservableProperty]
    public partial double ArrayPitchYMm { get; set; } = 10;

    /// <summary>
    /// Adds the open image or drawing as an array: <see cref="ArrayRows"/> × <see cref="ArrayColumns"/> layers, the first
    /// at the job's origin, each next one <see cref="ArrayPitchXMm"/> across and <see cref="ArrayPitchYMm"/> down; each
    /// copy is a layer, so the stage draws it and Start burns it where it is drawn.
    /// </summary>
    /// <returns>False (with <see cref="FileError"/> saying why) when nothing is open, it does not plan, or the array is out of range.</returns>
    public bool AddArray()
    {
        _activity.ThrowIfJobLocked();
        var rows = ArrayRows;
        var columns = ArrayColumns;
        if (rows < 1 || columns < 1 || (long)rows * columns < 2 || (long)rows * columns + Layers.Count > JobFile.MaxLayers)
        {
            FileError = $"an array of {rows} × {columns}: give at least 2 copies and at most {JobFile.MaxLayers - Layers.Count} in all (a job has at most {JobFile.MaxLayers} layers)";
            return false;
        }

        if (!(double.IsFinite(ArrayPitchXMm) && double.IsFinite(ArrayPitchYMm) && ArrayPitchXMm >= 0 && ArrayPitchYMm >= 0))
        {
            FileError = "an array's spacing: give 0 mm or more across and down";
            return false;
        }

        if (CurrentAsLayer(out var problem) is not { } layer)
        {
            FileError = problem + " before making an array of it";
            return false;
        }

        var layers = Layers.ToList();
        for (var r = 0; r < rows; r++)
        {
            for (var c = 0; c < columns; c++)
            {
                layers.Add(layer with
                {
                    Name = UniqueName($"{layer.Name} r{r + 1}c{c + 1}", layers),
                    Origin = new OriginMm(layer.Origin.X + (c * ArrayPitchXMm), layer.Origin.Y + (r * ArrayPitchYMm)),
                });
            }
        }

        FileError = null;
        Set(layers);
        return true;
    }

    /// <summary>The open image or drawing, with the values its fields have now, as a layer; null with <paramref name="problem"/> saying why.</summary>
    private JobLayer? CurrentAsLayer(out string? problem)
    {
        if (_job.ImagePath is not { } source)
        {
            problem = "open an image or drawing first: there is no job to save";
            return null;
        }

        if (_job.Engraving is null)
        {
            problem = "the open job does not plan (see the fields marked in red): set it right";
            return null;
        }

        var drawing = _job.IsDrawing;
        var now = _job.ToSettings();
        if (!drawing && now.Mode == PlanMode.Dots)
        {
            // A job file's image layer is rastered: written as one, a dots job would burn otherwise than it shows.
            problem = "the open job burns dots, and a job file's image layer is rastered: set the process to raster";
            return null;
        }

        problem = null;
        return new JobLayer
        {
            Name = Path.GetFileNameWithoutExtension(source) + (drawing && now.DrawingLayer is { } l ? " " + l : string.Empty),
            Source = source,
            Mode = drawing ? Mode(now.DrawingFill) : LayerMode.Raster,
            DrawingLayer = drawing ? now.DrawingLayer : null,
            WidthMm = now.SizeMode == SizeMode.Width ? now.WidthMm : drawing ? null : _job.Job!.Geometry.RequestedWidthMm,
            Origin = new OriginMm(now.OriginXMm, now.OriginYMm),
            SpeedMmPerS = now.BurnSpeedMmPerS,
            FrequencyHz = now.LaserFrequencyHz,
            Passes = now.Passes,
            ToleranceUm = drawing ? now.ToleranceUm : null,
            FillPitchUm = drawing ? now.FillPitchUm : null,
            Mask = drawing ? Core.Imaging.MaskOptions.Default : now.ToMask(),
        };
    }

    /// <summary>Replaces one layer (its name, mode, origin, speed, frequency or passes changed) and plans again.</summary>
    public void Update(int index, JobLayer layer)
    {
        ArgumentNullException.ThrowIfNull(layer);
        _activity.ThrowIfJobLocked();
        ArgumentOutOfRangeException.ThrowIfNegative(index);
        ArgumentOutOfRangeException.ThrowIfGreaterThanOrEqual(index, Layers.Count);
        var layers = Layers.ToList();
        layers[index] = layer;
        Set(layers);
    }

    public void Remove(int index)
    {
        _activity.ThrowIfJobLocked();
        ArgumentOutOfRangeException.ThrowIfNegative(index);
        ArgumentOutOfRangeException.ThrowIfGreaterThanOrEqual(index, Layers.Count);
        var layers = Layers.ToList();
        layers.RemoveAt(index);
        Set(layers);
    }

    /// <summary>Moves a layer earlier (<paramref name="by"/> -1) or later (+1) in the burn order; at either end nothing moves.</summary>
    public void Move(int index, int by)
    {
        _activity.ThrowIfJobLocked();
        var to = index + by;
        if (index < 0 || index >= Layers.Count || to < 0 || to >= Layers.Count)
        {
            return;
        }

        var layers = Layers.ToList();
        (layers[index], layers[to]) = (layers[to], layers[index]);
        Set(layers);
    }

    /// <summary>Empties the list: Start runs the single job again.</summary>
    public void Clear()
    {
        _activity.ThrowIfJobLocked();
        FileError = null;
        Set([]);
    }

    /// <summary>Throws <see cref="MachineBusyException"/> while an operation holds the job (a job file chosen in the page waits for it before it is kept).</summary>
    public void ThrowIfLocked() => _activity.ThrowIfJobLocked();

    /// <summary>A job file the page could not hand over (too large, interrupted, refused during a run): why, as <see cref="FileError"/>.</summary>
    public void ReportFileError(string problem) => FileError = problem;

    /// <summary>A job file was opened: its layers are a new artwork (undo starts anew).</summary>
    public event EventHandler? Opened;

    /// <summary>Puts <paramref name="layers"/> back as the job of layers (undo and redo) and plans them again.</summary>
    public void Restore(IReadOnlyList<JobLayer> layers)
    {
        ArgumentNullException.ThrowIfNull(layers);
        _activity.ThrowIfJobLocked();
        Set(layers);
    }

    /// <summary>Opens a job file (as <c>--job</c> reads it); a bad file leaves the layers as they were and says why.</summary>
    public bool Open(string path)
    {
        ArgumentException.ThrowIfNullOrWhiteSpace(path);
        _activity.ThrowIfJobLocked();
        IReadOnlyList<JobLayer> layers;
        try
        {
            layers = _files.Load(path);
        }
        catch (Exception ex) when (ex is PlanException or IOException or UnauthorizedAccessException)
        {
            FileError = ex.Message;
            return false;
        }

        if (layers.Count == 1)
        {
            return OpenSingle(path, layers[0]);
        }

        FileError = null;
        JobPath = Path.GetFullPath(path);
        _inFile = layers;
        Set(layers);
        Opened?.Invoke(this, EventArgs.Empty);
        return true;
    }

    /// <summary>
    /// A job file of one layer opens as the single job it was saved from: its image or drawing opened, then its values
    /// put in the fields (what a layer leaves out, the machine profile's); the layers, if any, are emptied.
    /// </summary>
    private bool OpenSingle(string path, JobLayer layer)
    {
        _openingSingle = true;
        try
        {
            if (!_job.LoadImage(layer.Source))
            {
                FileError = $"{path}: its image or drawing {layer.Source} did not open: {_job.Errors.GetValueOrDefault(JobViewModel.ImageField) ?? "see the Image panel"}";
                return false;
            }

            var profile = JobViewModel.FromProfile(_job.Profile);
            var drawing = layer.Mode != LayerMode.Raster;
            _job.Apply(_job.ToSettings().WithMask(layer.Mask) with
            {
                ImagePath = null,
                SizeMode = layer.WidthMm is not null ? SizeMode.Width : SizeMode.Pitch,
                WidthMm = layer.WidthMm ?? _job.ToSettings().WidthMm,
                OriginXMm = layer.Origin.X,
                OriginYMm = layer.Origin.Y,
                BurnSpeedMmPerS = layer.SpeedMmPerS ?? profile.BurnSpeedMmPerS,
                LaserFrequencyHz = layer.FrequencyHz ?? profile.LaserFrequencyHz,
                Passes = layer.Passes,
                Mode = PlanMode.Raster,
                DrawingFill = layer.Fill,
                DrawingLayer = drawing ? layer.DrawingLayer : null,
                ToleranceUm = layer.ToleranceUm ?? VectorOptions.Default.ToleranceUm,
                FillPitchUm = layer.FillPitchUm ?? VectorOptions.Default.FillPitchUm,
            });
            FileError = null;
            JobPath = Path.GetFullPath(path);
            _inFile = null;
            Set([]);
            Opened?.Invoke(this, EventArgs.Empty);
            return true;
        }
        finally
        {
            _openingSingle = false;
        }
    }

    /// <summary>
    /// Writes the layers, or with none the open image or drawing as one layer, to a job file the command line runs
    /// (<c>engrave --job FILE</c>) and Open opens back as the same job.
    /// </summary>
    public bool Save(string path)
    {
        ArgumentException.ThrowIfNullOrWhiteSpace(path);
        if (ToSave(out var problem) is not { } layers)
        {
            FileError = problem;
            return false;
        }

        if (!path.EndsWith(".json", StringComparison.OrdinalIgnoreCase))
        {
            FileError = $"{path}: a job file ends in .json";
            return false;
        }

        try
        {
            _files.Save(path, layers);
        }
        catch (Exception ex) when (ex is IOException or UnauthorizedAccessException or ArgumentException or NotSupportedException)
        {
            FileError = $"{path}: {ex.Message}";
            return false;
        }

        FileError = null;
        JobPath = Path.GetFullPath(path);

        // A single job saved is not a job of layers: a run of it logs no job file to resume from.
        _inFile = IsActive ? Layers : null;
        OnPropertyChanged(nameof(UnchangedJobFile));
        return true;
    }

    /// <summary>One layer's plan (null while the layers do not plan).</summary>
    public JobPart? Planned(int index) => Job is { } job && index >= 0 && index < job.Layers.Count ? job.Layers[index] : null;

    private static LayerMode Mode(VectorFillMode fill) => fill switch
    {
        VectorFillMode.Fill => LayerMode.Fill,
        VectorFillMode.Both => LayerMode.Both,
        _ => LayerMode.Outline,
    };

    private string UniqueName(string name, IReadOnlyList<JobLayer>? among = null)
    {
        var taken = (among ?? Layers).Select(l => l.Name).ToHashSet(StringComparer.Ordinal);
        if (!taken.Contains(name))
        {
            return name;
        }

        var n = 2;
        while (taken.Contains($"{name} {n}"))
        {
            n++;
        }

        return $"{name} {n}";
    }

    private void Set(IReadOnlyList<JobLayer> layers)
    {
        Layers = layers;
        OnPropertyChanged(nameof(UnchangedJobFile));
        Replan();
    }

    private void Replan()
    {
        LayeredJob? job = null;
        string? error = null;
        int? errorLayer = null;
        if (Layers.Count > 0)
        {
            try
            {
                job = _files.Prepare(Layers, _job.Profile);
                var outside = job.Layers.ToList().FindIndex(l => !l.FitsTravel);
                if (outside >= 0)
                {
                    error = $"layer \"{job.Layers[outside].Layer.Name}\" does not fit the stage's travel: move its origin or make it smaller";
                    errorLayer = outside;
                }
            }
            catch (PlanException ex)
            {
                error = ex.Message;
                errorLayer = ex.Layer;
            }
        }

        Job = job;
        Error = error;
        ErrorLayer = errorLayer;
        PlanVersion++;
    }
}
