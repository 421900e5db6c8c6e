using System.Text.Json;
using LaserEngrave.Core.Jobs;

namespace LaserEngrave.App.Services;

/// <summary>Presets as JSON in presets.json beside settings.json.</summary>
public sealed class JsonPresetStore(string path) : IPresetStore
{
    public IReadOnlyList<ProcessPreset> Load()
    {
        try
        {
            return File.Exists(path) ? ProcessPreset.FromJson(File.ReadAllText(path)) : ProcessPreset.Examples;
        }
        catch (Exception ex) when (ex is IOException or UnauthorizedAccessException or JsonException or ArgumentException)
        {
            // A damaged library must not stop the app; the examples stand in until the next save.
            return ProcessPreset.Examples;
        }
    }

    public void Save(IReadOnlyList<ProcessPreset> presets)
    {
        Directory.CreateDirectory(Path.GetDirectoryName(Path.GetFullPath(path))!);
        File.WriteAllText(path, ProcessPreset.ToJson(presets));
    }
}
