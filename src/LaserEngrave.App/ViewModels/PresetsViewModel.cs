using System.Text.Json;
using CommunityToolkit.Mvvm.ComponentModel;
using CommunityToolkit.Mvvm.Input;
using LaserEngrave.App.Services;
using LaserEngrave.Core.Geometry;
using LaserEngrave.Core.Jobs;

namespace LaserEngrave.App.ViewModels;

/// <summary>The preset library: apply a preset to the job, keep the job's process values as one, import and export them as JSON.</summary>
public sealed partial class PresetsViewModel : ObservableObject
{
    private readonly IPresetStore _store;
    private readonly IJobSession _job;

    public PresetsViewModel(IPresetStore store, IJobSession job)
    {
        ArgumentNullException.ThrowIfNull(store);
        ArgumentNullException.ThrowIfNull(job);
        _store = store;
        _job = job;
        Presets = store.Load();
        Selected = Presets.FirstOrDefault()?.Name;
        _job.PropertyChanged += (_, e) =>
        {
            if (e.PropertyName == nameof(IJobSession.LockedBecause))
            {
                ApplyCommand.NotifyCanExecuteChanged();
            }
        };
    }

    [ObservableProperty]
    public partial IReadOnlyList<ProcessPreset> Presets { get; private set; }

    [ObservableProperty]
    [NotifyCanExecuteChangedFor(nameof(ApplyCommand), nameof(DeleteCommand))]
    public partial string? Selected { get; set; }

    /// <summary>The name the job's values are kept under.</summary>
    [ObservableProperty]
    [NotifyCanExecuteChangedFor(nameof(SaveCurrentCommand))]
    public partial string? NewName { get; set; }

    [ObservableProperty]
    public partial string? NewNotes { get; set; }

    [ObservableProperty]
    public partial string? Error { get; private set; }

    public ProcessPreset? SelectedPreset => Presets.FirstOrDefault(p => p.Name == Selected);

    public bool HasSelection => SelectedPreset is not null;

    /// <summary>A preset selected, and the job free to change (the interlock decides: not during a run, homing or a test move).</summary>
    public bool CanApply => HasSelection && _job.LockedBecause is null;

    public bool CanSaveCurrent => !string.IsNullOrWhiteSpace(NewName);

    /// <summary>
    /// Sets the job's process values (frequency, speeds, passes, overscan) from the selected preset. A preset's pitch
    /// changes the artwork's size, so it is not applied here: when it differs from the job's it is offered as
    /// <see cref="PitchOffer"/>, with the size it would make, until <see cref="ApplyPitchCommand"/> or <see cref="KeepSizeCommand"/>.
    /// </summary>
    [RelayCommand(CanExecute = nameof(CanApply))]
    private void Apply()
    {
        if (SelectedPreset is not { } preset)
        {
            return;
        }

        Error = null;
        PitchOffer = null;
        if (Refusal(preset) is { } refused)
        {
            // The job rules answer as they do for the fields: a preset the machine cannot run changes nothing.
            Error = refused;
            return;
        }

        try
        {
            _job.Change(s => s with
            {
                LaserFrequencyHz = preset.LaserFrequencyHz,
                BurnSpeedMmPerS = preset.BurnSpeedMmPerS,
                TravelSpeedMmPerS = preset.TravelSpeedMmPerS,
                Passes = preset.Passes,
                OverscanMm = preset.OverscanMm,
            });
        }
        catch (MachineBusyException ex)
        {
            Error = ex.Message;
            return;
        }

        var pitchUm = _job.ToSettings().PitchUm;
        if (Math.Abs(preset.PitchUm - pitchUm) > 1e-9)
        {
            PitchOffer = new PresetPitchOffer(preset.Name, preset.PitchUm, pitchUm, CurrentSize(), SizeAt(preset.PitchUm));
        }
    }

    /// <summary>A preset's pitch not applied yet, shown with the job's size now and the size it would make.</summary>
    [ObservableProperty]
    [NotifyCanExecuteChangedFor(nameof(ApplyPitchCommand), nameof(KeepSizeCommand))]
    public partial PresetPitchOffer? PitchOffer { get; private set; }

    private bool HasPitchOffer => PitchOffer is not null;

    /// <summary>Uses the offered pitch: the job is resized to it (as setting the pitch field does).</summary>
    [RelayCommand(CanExecute = nameof(HasPitchOffer))]
    private void ApplyPitch()
    {
        if (PitchOffer is not { } offer)
        {
            return;
        }

        try
        {
            _job.Change(s => s with { PitchUm = offer.PitchUm, SizeMode = SizeMode.Pitch });
            PitchOffer = null;
        }
        catch (MachineBusyException ex)
        {
            Error = ex.Message;
        }
    }

    /// <summary>Keeps the job's pitch and size; the preset's pitch is dropped.</summary>
    [RelayCommand(CanExecute = nameof(HasPitchOffer))]
    private void KeepSize() => PitchOffer = null;

    private (double WidthMm, double HeightMm)? CurrentSize() => _job.Job is { } job
        ? (job.Geometry.AchievedWidthMm, job.Geometry.AchievedHeightMm)
        : null;

    /// <summary>An image's size at <paramref name="pitchUm"/>: one pixel a pitch (a drawing keeps its size).</summary>
    private (double WidthMm, double HeightMm)? SizeAt(double pitchUm) => _job.ImageInfo is { } info && !_job.IsDrawing
        ? (Units.StepsToMm(info.Width, pitchUm), Units.StepsToMm(info.Height, pitchUm))
        : null;

    /// <summary>Keeps the job's process values under <see cref="NewName"/>, replacing a preset of that name.</summary>
    [RelayCommand(CanExecute = nameof(CanSaveCurrent))]
    private void SaveCurrent()
    {
        var name = NewName!.Trim();
        var now = _job.ToSettings();
        var preset = new ProcessPreset
        {
            Name = name,
            LaserFrequencyHz = now.LaserFrequencyHz,
            BurnSpeedMmPerS = now.BurnSpeedMmPerS,
            TravelSpeedMmPerS = now.TravelSpeedMmPerS,
            Passes = now.Passes,
            PitchUm = now.PitchUm,
            OverscanMm = now.OverscanMm,
            Notes = string.IsNullOrWhiteSpace(NewNotes) ? null : NewNotes.Trim(),
        };
        if (Store([.. Presets.Where(p => p.Name != name), preset]))
        {
            Selected = name;
            NewName = null;
            NewNotes = null;
        }
    }

    [RelayCommand(CanExecute = nameof(HasSelection))]
    private void Delete()
    {
        if (Store([.. Presets.Where(p => p.Name != Selected)]))
        {
            Selected = Presets.FirstOrDefault()?.Name;
        }
    }

    /// <summary>The library as JSON, to keep or hand to another lab.</summary>
    public string ExportJson() => ProcessPreset.ToJson(Presets);

    /// <summary>Adds the presets in <paramref name="json"/>, replacing those of the same name; a bad file changes nothing and says why.</summary>
    public bool Import(string json)
    {
        IReadOnlyList<ProcessPreset> imported;
        try
        {
            imported = ProcessPreset.FromJson(json);
        }
        catch (Exception ex) when (ex is JsonException or ArgumentException or NotSupportedException)
        {
            Error = $"not imported: {ex.Message}";
            return false;
        }

        if (imported.Select(Refusal).FirstOrDefault(r => r is not null) is { } refused)
        {
            Error = $"not imported: {refused}";
            return false;
        }

        var names = imported.Select(p => p.Name).ToHashSet();
        return Store([.. Presets.Where(p => !names.Contains(p.Name)), .. imported]);
    }

    /// <summary>What the job rules refuse in <paramref name="preset"/> on this machine, one line naming the preset; null when nothing.</summary>
    private string? Refusal(ProcessPreset preset) => preset.Check(Core.Geometry.MachineLimits.Of(_job.Profile)) is [_, ..] problems
        ? $"preset \"{preset.Name}\": {string.Join("; ", problems.Select(p => p.Message))}"
        : null;

    private bool Store(IReadOnlyList<ProcessPreset> presets)
    {
        try
        {
            _store.Save(presets);
        }
        catch (Exception ex) when (ex is IOException or UnauthorizedAccessException)
        {
            Error = $"presets not saved: {ex.Message}";
            return false;
        }

        Error = null;
        Presets = presets;
        OnPropertyChanged(nameof(SelectedPreset));
        ApplyCommand.NotifyCanExecuteChanged();
        DeleteCommand.NotifyCanExecuteChanged();
        return true;
    }
}

/// <summary>A pitch a preset carries, offered before it resizes the job.</summary>
/// <param name="Preset">The preset's name.</param>
/// <param name="PitchUm">The preset's pitch.</param>
/// <param name="JobPitchUm">The job's pitch now.</param>
/// <param name="JobSize">The job's size now, if it is planned.</param>
/// <param name="NewSize">The size the pitch would make, for an image.</param>
public sealed record PresetPitchOffer(string Preset, double PitchUm, double JobPitchUm, (double WidthMm, double HeightMm)? JobSize, (double WidthMm, double HeightMm)? NewSize);
