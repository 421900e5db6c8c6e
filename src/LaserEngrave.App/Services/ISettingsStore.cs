namespace LaserEngrave.App.Services;

/// <summary>Reads and writes <see cref="AppSettings"/>.</summary>
public interface ISettingsStore
{
    /// <summary>The saved settings, or the defaults when there are none or they cannot be read.</summary>
    AppSettings Load();

    void Save(AppSettings settings);
}
