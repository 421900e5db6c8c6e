using LaserEngrave.Core.Jobs;
namespace LaserEngrave.App.Services;

/// <summary>The preset library beside the settings.</summary>
public interface IPresetStore
{
    /// <summary>The saved presets, or the shipped examples when none were saved yet.</summary>
    IReadOnlyList<ProcessPreset> Load();

    void Save(IReadOnlyList<ProcessPreset> presets);
}
